# Installs the pinned node-mavlink into INSTALL_DIR (cmake -P; run by the CTest fixture
# node_mavlink_install). Inputs: NODE, NPM, SOURCE_DIR (this folder), INSTALL_DIR.
if(NOT NODE OR NOT EXISTS "${NODE}")
  message(FATAL_ERROR "node-mavlink conformance: Node.js (node) not found. Install Node.js >= 18 and npm, then re-run cmake.")
endif()
if(NOT NPM OR NOT EXISTS "${NPM}")
  message(FATAL_ERROR "node-mavlink conformance: npm not found. Install npm (it comes with Node.js), then re-run cmake.")
endif()

file(MAKE_DIRECTORY "${INSTALL_DIR}")
set(_stamp "${INSTALL_DIR}/.hitl-installed")
file(SHA256 "${SOURCE_DIR}/package.json" _h1)
file(SHA256 "${SOURCE_DIR}/package-lock.json" _h2)
set(_want "${_h1} ${_h2}")
if(EXISTS "${_stamp}" AND EXISTS "${INSTALL_DIR}/node_modules/node-mavlink/package.json")
  file(READ "${_stamp}" _have)
  if(_have STREQUAL _want)
    message(STATUS "node-mavlink already installed in ${INSTALL_DIR}")
    return()
  endif()
endif()

file(COPY "${SOURCE_DIR}/package.json" "${SOURCE_DIR}/package-lock.json" DESTINATION "${INSTALL_DIR}")
execute_process(
  COMMAND "${NPM}" install --no-audit --no-fund --prefix "${INSTALL_DIR}"
  WORKING_DIRECTORY "${INSTALL_DIR}"
  RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "node-mavlink conformance: 'npm install' failed (${_rc}); is the npm registry reachable?")
endif()

execute_process(
  COMMAND "${NODE}" -p "require('node-mavlink/package.json').version + ' ' + require('mavlink-mappings/package.json').version"
  WORKING_DIRECTORY "${INSTALL_DIR}"
  OUTPUT_VARIABLE _versions OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0 OR NOT _versions STREQUAL "2.3.0 1.0.21-20250824-1")
  message(FATAL_ERROR "node-mavlink conformance: expected node-mavlink 2.3.0 and mavlink-mappings 1.0.21-20250824-1, found '${_versions}'")
endif()
file(WRITE "${_stamp}" "${_want}")
message(STATUS "installed node-mavlink ${_versions} in ${INSTALL_DIR}")
