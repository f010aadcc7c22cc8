# target/ configured on its own: the board packages voxl-hitl-vio-server and voxl-hitl-px4-scripts
# (.deb, arm64 with the toolchain file aarch64-linux-gnu.cmake beside this one). Builds only what
# they need: base/ (the codec and the contract), target/vio-server, target/px4/scripts and target/adb-relay.
#   cmake -S target -B /tmp/board -DCMAKE_TOOLCHAIN_FILE=target/cmake/aarch64-linux-gnu.cmake
#   cmake --build /tmp/board -j2 && (cd /tmp/board && cpack -G DEB)
set(HITL_REPO_ROOT ${CMAKE_CURRENT_SOURCE_DIR}/..)
set(CMAKE_CXX_STANDARD 20)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_CXX_EXTENSIONS OFF)
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()
find_program(CCACHE_PROGRAM ccache)
if(CCACHE_PROGRAM)
  set(CMAKE_CXX_COMPILER_LAUNCHER ${CCACHE_PROGRAM})
endif()
set(HITL_WARNINGS -Wall -Wextra -Wpedantic -Wshadow=local -Wno-missing-field-initializers)
set(HITL_BOARD_VERSION ${PROJECT_VERSION})
set(HITL_BOARD_PACKAGES ON)
option(HITL_STATIC_BOARD_BINARIES "Link the board programs statically (they then run on the board's older glibc)" ON)

find_package(Threads REQUIRED)

# nlohmann/json is header-only: the build machine's copy serves any target. Only its own directory
# goes on the include path, never the build machine's /usr/include, which a cross build must not see.
find_path(HITL_NLOHMANN_JSON_DIR nlohmann/json.hpp NO_CMAKE_FIND_ROOT_PATH)
if(NOT HITL_NLOHMANN_JSON_DIR)
  message(FATAL_ERROR "nlohmann/json.hpp not found: install nlohmann-json3-dev (scripts/install-deps.sh)")
endif()
set(HITL_HEADER_ONLY_INCLUDE ${CMAKE_BINARY_DIR}/header-only-include)
file(MAKE_DIRECTORY ${HITL_HEADER_ONLY_INCLUDE})
file(CREATE_LINK ${HITL_NLOHMANN_JSON_DIR}/nlohmann ${HITL_HEADER_ONLY_INCLUDE}/nlohmann SYMBOLIC)
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED)
set_target_properties(nlohmann_json::nlohmann_json PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${HITL_HEADER_ONLY_INCLUDE})

# base/ (the codec, the contract) as a library, as the host build uses it.
set(HITL_SOURCE_ROOT ${HITL_REPO_ROOT})
include(${HITL_REPO_ROOT}/cmake/layers.cmake)
add_subdirectory(${HITL_REPO_ROOT}/base ${CMAKE_BINARY_DIR}/base)
add_subdirectory(vio-server)
add_subdirectory(px4/scripts)
# hitl-adb-relay (the board end of `hitl sim --adb`) ships in voxl-hitl-px4-scripts too.
if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/adb-relay/CMakeLists.txt)
  add_subdirectory(adb-relay)
endif()

# --- packaging: one .deb per install component --------------------------------------------------
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(aarch64|arm64)$")
  set(HITL_DEB_ARCH arm64)
elseif(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64)$")
  set(HITL_DEB_ARCH amd64)
else()
  message(FATAL_ERROR "no Debian architecture known for ${CMAKE_SYSTEM_PROCESSOR}")
endif()
set(HITL_DEBIAN_DIR ${CMAKE_CURRENT_SOURCE_DIR}/debian)

set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL voxl-hitl-vio-server voxl-hitl-px4-scripts)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE ${HITL_DEB_ARCH})
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "hitl developers")
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_STRIP_FILES ON)  # with the toolchain's strip (aarch64-linux-gnu-strip when cross-compiling)

set(CPACK_DEBIAN_VOXL-HITL-VIO-SERVER_PACKAGE_NAME voxl-hitl-vio-server)
set(CPACK_DEBIAN_VOXL-HITL-VIO-SERVER_DESCRIPTION
  "HITL ODOMETRY to ModalAI's VIO MPA pipes
voxl-hitl-vio-server receives MAVLink ODOMETRY over UDP (port 14570) from hitl sim and
publishes each pose as vio_data_t on the MPA pipe hitl_vio and ext_vio_data_t on
hitl_vio_extended, for voxl-vision-hub with en_hitl.")
set(CPACK_DEBIAN_VOXL-HITL-VIO-SERVER_PACKAGE_CONTROL_EXTRA
  ${HITL_DEBIAN_DIR}/voxl-hitl-vio-server/conffiles
  ${HITL_DEBIAN_DIR}/voxl-hitl-vio-server/postinst
  ${HITL_DEBIAN_DIR}/voxl-hitl-vio-server/prerm
  ${HITL_DEBIAN_DIR}/voxl-hitl-vio-server/postrm)

set(CPACK_DEBIAN_VOXL-HITL-PX4-SCRIPTS_PACKAGE_NAME voxl-hitl-px4-scripts)
set(CPACK_DEBIAN_VOXL-HITL-PX4-SCRIPTS_DESCRIPTION
  "PX4 HITL start script and default parameters for VOXL2 / M0197
voxl-px4-hitl starts PX4 for hardware-in-the-loop simulation in the order of the HITL
spec's startup sequence and loads the HITL default parameter set on first boot. While
installed it takes the place of voxl-px4's own /usr/bin/voxl-px4-hitl (dpkg-divert).")
set(CPACK_DEBIAN_VOXL-HITL-PX4-SCRIPTS_PACKAGE_CONTROL_EXTRA
  ${HITL_DEBIAN_DIR}/voxl-hitl-px4-scripts/preinst
  ${HITL_DEBIAN_DIR}/voxl-hitl-px4-scripts/postrm)

include(CPack)
