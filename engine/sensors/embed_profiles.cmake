# Writes a C++ source holding every sensor profile (engine/sensors/profiles/*.json) as {file name
# without .json, text}, so that the binary carries the one copy of each data file:
#   cmake -DDIR=profiles -DOUTPUT=file.cpp -P embed_profiles.cmake
file(GLOB files ${DIR}/*.json)
list(SORT files)
set(body "")
foreach(f ${files})
  get_filename_component(stem ${f} NAME_WE)
  file(READ ${f} text)
  string(APPEND body "    {\"${stem}\", R\"hitlprofile(${text})hitlprofile\"},\n")
endforeach()
file(WRITE ${OUTPUT} "// Generated from ${DIR}/*.json at build time. Do not edit.\n#include \"engine/sensors/sensor_profiles.h\"\nnamespace hitl::sensors {\nconst std::vector<EmbeddedProfile>& embedded_profiles() {\n  static const std::vector<EmbeddedProfile> profiles{\n${body}  };\n  return profiles;\n}\n}  // namespace hitl::sensors\n")
