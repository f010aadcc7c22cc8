# Writes a C++ source holding the text of INPUT as NAME (a const char* in namespace NAMESPACE), so
# the build compiles in a data file rather than a second copy of its values.
#   cmake -DINPUT=file -DOUTPUT=file.cpp -DNAME=kText -DNAMESPACE=hitl::vio -P embed_text.cmake
file(READ ${INPUT} text)
file(WRITE ${OUTPUT} "// Generated from ${INPUT} at build time. Do not edit.\nnamespace ${NAMESPACE} {\nextern const char* const ${NAME};\nconst char* const ${NAME} = R\"hitltext(${text})hitltext\";\n}\n")
