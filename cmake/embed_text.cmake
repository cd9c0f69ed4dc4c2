# Generates a C++ source with one function returning a file's text, so the binary carries it.
# Inputs: INPUT (file), OUTPUT (.cpp), FUNCTION (qualified name, e.g. tourmap::api::openapi_yaml).
file(READ "${INPUT}" content)
string(REPLACE "::" ";" parts "${FUNCTION}")
list(POP_BACK parts fname)
list(JOIN parts "::" ns)
file(WRITE "${OUTPUT}.tmp" "// Generated from ${INPUT} by cmake/embed_text.cmake. Do not edit.\n#include <string_view>\n\nnamespace ${ns} {\n\nstd::string_view ${fname}() {\n  static constexpr std::string_view text = R\"tourmap_text(${content})tourmap_text\";\n  return text;\n}\n\n}  // namespace ${ns}\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${OUTPUT}.tmp" "${OUTPUT}")
file(REMOVE "${OUTPUT}.tmp")
