# Generates a C++ source with one function returning a file's text, so the binary carries it.
# Inputs: INPUT (file), OUTPUT (.cpp), FUNCTION (qualified name, e.g. tourmap::api::openapi_yaml).
# The text goes in as raw string literals of at most 60,000 bytes each, cut after a line: C++
# compilers need only take literals of 65,536 characters ([implimits]; clang warns beyond, and
# api/openapi.yaml is longer), and a cut at a line end never splits a UTF-8 sequence.
file(READ "${INPUT}" content)
string(REPLACE "::" ";" parts "${FUNCTION}")
list(POP_BACK parts fname)
list(JOIN parts "::" ns)
set(literals "")
while(NOT content STREQUAL "")
  string(LENGTH "${content}" length)
  if(length GREATER 60000)
    string(SUBSTRING "${content}" 0 60000 head)
    string(FIND "${head}" "\n" cut REVERSE)
    if(cut LESS 0)
      set(cut 59999)  # no line end: cut anywhere (a text without newlines is not UTF-8 prose)
    endif()
    math(EXPR cut "${cut} + 1")
  else()
    set(cut ${length})
  endif()
  string(SUBSTRING "${content}" 0 ${cut} piece)
  string(SUBSTRING "${content}" ${cut} -1 content)
  string(APPEND literals "      std::string_view(R\"tourmap_text(${piece})tourmap_text\"),\n")
endwhile()
file(WRITE "${OUTPUT}.tmp" "// Generated from ${INPUT} by cmake/embed_text.cmake. Do not edit.\n#include <string>\n#include <string_view>\n\nnamespace ${ns} {\n\nstd::string_view ${fname}() {\n  static const std::string text = [] {\n    std::string s;\n    for (std::string_view part : {\n${literals}      std::string_view()})\n      s += part;\n    return s;\n  }();\n  return text;\n}\n\n}  // namespace ${ns}\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${OUTPUT}.tmp" "${OUTPUT}")
file(REMOVE "${OUTPUT}.tmp")
