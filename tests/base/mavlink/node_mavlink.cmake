# Byte-for-byte conformance against the npm package node-mavlink (pinned in node/package.json
# and node/package-lock.json). Included from tests/base/mavlink/CMakeLists.txt.
#
#   node_mavlink_install   CTest fixture (FIXTURES_SETUP node_mavlink): npm install into
#                          <build>/tests/base/mavlink/node_mavlink; fails clearly without node/npm.
#   NodeMavlinkConformance.*  gtest (label conformance): see node_mavlink_test.cpp.
#
# Run: ctest --test-dir <build> -L conformance   (needs node >= 18, npm and the npm registry)

find_program(HITL_NODE_EXECUTABLE NAMES node nodejs DOC "Node.js, for the node-mavlink conformance test")
find_program(HITL_NPM_EXECUTABLE NAMES npm DOC "npm, to install node-mavlink for the conformance test")
set(HITL_NODE_MAVLINK_DIR "${CMAKE_CURRENT_BINARY_DIR}/node_mavlink")
set(_hitl_node_src "${CMAKE_CURRENT_LIST_DIR}/node")

add_test(NAME node_mavlink_install
  COMMAND ${CMAKE_COMMAND}
    "-DNODE=${HITL_NODE_EXECUTABLE}" "-DNPM=${HITL_NPM_EXECUTABLE}"
    "-DSOURCE_DIR=${_hitl_node_src}" "-DINSTALL_DIR=${HITL_NODE_MAVLINK_DIR}"
    -P "${_hitl_node_src}/install.cmake")
set_tests_properties(node_mavlink_install PROPERTIES
  FIXTURES_SETUP node_mavlink LABELS conformance TIMEOUT 600)

# Not hitl_add_test(): the discovered tests must require the fixture above.
# The values and the cases it checks are in node_mavlink_values.h and node_mavlink_cases.h.
add_executable(node_mavlink_test "${CMAKE_CURRENT_LIST_DIR}/node_mavlink_test.cpp")
target_include_directories(node_mavlink_test PRIVATE ${PROJECT_SOURCE_DIR})
target_link_libraries(node_mavlink_test PRIVATE hitl_mavlink GTest::gtest_main Threads::Threads)
target_compile_options(node_mavlink_test PRIVATE ${HITL_WARNINGS})
target_compile_definitions(node_mavlink_test PRIVATE
  HITL_NODE_EXECUTABLE="${HITL_NODE_EXECUTABLE}"
  HITL_NODE_MAVLINK_DIR="${HITL_NODE_MAVLINK_DIR}"
  HITL_NODE_CHECK_JS="${_hitl_node_src}/check.js")
gtest_discover_tests(node_mavlink_test DISCOVERY_TIMEOUT 60
  PROPERTIES LABELS conformance FIXTURES_REQUIRED node_mavlink TIMEOUT 300)
