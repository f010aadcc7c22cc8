# Writes a C++ source holding base/contract/hitl-defaults.params as a string, so the build compiles
# in the one data file rather than a second copy of its values.
file(READ ${INPUT} text)
file(WRITE ${OUTPUT} "// Generated from ${INPUT} at build time. Do not edit.\nnamespace hitl::vehicle {\nextern const char* const kHitlDefaultParamsText;\nconst char* const kHitlDefaultParamsText = R\"hitlparams(${text})hitlparams\";\n}\n")
