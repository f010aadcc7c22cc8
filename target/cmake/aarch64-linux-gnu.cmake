# Cross-compiling the board packages for the VOXL2's arm64 apps processor with Debian's
# g++-aarch64-linux-gnu (scripts/install-deps.sh --test installs it):
#   cmake -S target -B /tmp/board -DCMAKE_TOOLCHAIN_FILE=target/cmake/aarch64-linux-gnu.cmake
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(HITL_CROSS_TRIPLE aarch64-linux-gnu)
find_program(CMAKE_CXX_COMPILER NAMES ${HITL_CROSS_TRIPLE}-g++ REQUIRED)

# Libraries and headers come from the cross sysroot only, never from the build machine; programs
# (cmake, pkg-config) from the build machine. Header-only packages are handled in board_packages.cmake.
set(CMAKE_FIND_ROOT_PATH /usr/${HITL_CROSS_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# pkg-config must not offer the build machine's .pc files either.
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/${HITL_CROSS_TRIPLE}/pkgconfig:/usr/${HITL_CROSS_TRIPLE}/lib/pkgconfig)
set(ENV{PKG_CONFIG_SYSROOT_DIR} /)
