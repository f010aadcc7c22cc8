# Writes a C++ source holding a text file as one string constant (NAME in namespace hitl::cli), so
# that the binary carries the one copy of the file: cmake -DINPUT=... -DOUTPUT=... -DNAME=... -P embed_text.cmake
file(READ ${INPUT} text)
file(WRITE ${OUTPUT} "// Generated from ${INPUT} at build time. Do not edit.\nnamespace hitl::cli {\nextern const char* const ${NAME};\nconst char* const ${NAME} = R\"hitltext(${text})hitltext\";\n}\n")
