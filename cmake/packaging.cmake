# Installing hitl on a host (cmake --install BUILD_DIR --component hitl) and its Debian package
# (cpack -G DEB in the build directory): the binary, the shell completions, the man page, the
# documentation and the examples, in the places the FHS and each shell look (docs/ecosystem.md).
#
# Everything here is install component `hitl`, and the package is made of that component only:
# the board packages (voxl-hitl-vio-server, voxl-hitl-px4-scripts) come from target/ configured on
# its own with its own CPack project (target/cmake/board_packages.cmake); the two never mix.
include(GNUInstallDirs)
# cpack (and the `install` target) package what is built rather than building every target (tests,
# benchmarks) first: build hitl, then package it. A missing binary is an error naming it.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY TRUE)

# install(TARGETS hitl ... COMPONENT hitl) is in cli/CMakeLists.txt.
install(FILES ${PROJECT_SOURCE_DIR}/completions/hitl.bash
        DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions RENAME hitl COMPONENT hitl)
install(FILES ${PROJECT_SOURCE_DIR}/completions/_hitl
        DESTINATION ${CMAKE_INSTALL_DATADIR}/zsh/vendor-completions COMPONENT hitl)
install(FILES ${PROJECT_SOURCE_DIR}/completions/hitl.fish
        DESTINATION ${CMAKE_INSTALL_DATADIR}/fish/vendor_completions.d COMPONENT hitl)
install(FILES ${PROJECT_SOURCE_DIR}/docs/hitl.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT hitl)
# The pages and the images they show (report-demo.png, the Allan plots).
file(GLOB hitl_user_docs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/docs/*.md ${PROJECT_SOURCE_DIR}/docs/*.png ${PROJECT_SOURCE_DIR}/docs/*.svg)
install(FILES ${hitl_user_docs} ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT hitl)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/examples/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples COMPONENT hitl
        FILES_MATCHING PATTERN "*.json" PATTERN "*.toml"
        PATTERN "*.sh" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)

set(CPACK_PACKAGE_NAME hitl)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL hitl)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_HITL_PACKAGE_NAME hitl)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "hitl developers")
set(CPACK_DEBIAN_PACKAGE_SECTION electronics)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# Depends: the Debian packages of the shared libraries the binary links, found by dpkg-shlibdeps.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# adb carries the board link over USB without USB-Ethernet (hitl sim --adb, hitl bridge --adb).
set(CPACK_DEBIAN_HITL_PACKAGE_SUGGESTS "adb, bash-completion")
# gnuplot draws hitl report's plots (and the report hitl demo writes); a program, not a library.
# libjs-dygraphs is inlined into the interactive page (read at run time from /usr/share/javascript).
set(CPACK_DEBIAN_HITL_PACKAGE_RECOMMENDS "gnuplot-nox, libjs-dygraphs")
# The package's one-line summary is the project's DESCRIPTION; this is the text below it.
set(CPACK_DEBIAN_HITL_DESCRIPTION
  "hitl runs and diagnoses hardware-in-the-loop simulation of a PX4 x500 quadcopter whose flight
stack runs on a ModalAI VOXL2 / M0197 board: an embedded Simbody model of the x500 bridged to the
board over MAVLink (hitl sim), an emulated board for machines without one (hitl target), and tools
to operate the board and measure its MAVLink links (params, arm, fly, shell, inspect).")
include(CPack)
