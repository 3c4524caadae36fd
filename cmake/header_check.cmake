# Every public header compiles on its own (design rule). A header whose own source file
# (foo.h beside foo.cpp) includes it before anything else is already compiled on its own
# by that source file's compile; every other header gets a generated translation unit
# holding only its #include. Checking the first include is enough: the source file's
# other includes and code come after it, so nothing they declare can help the header.
#
# bsg_header_check_sources(OUT_VAR OUTPUT_DIR HEADER...): the generated sources to compile,
# one per header that its own source file does not already check.
function(bsg_header_check_sources out_var output_dir)
  set(sources)
  foreach(header ${ARGN})
    file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${header})
    get_filename_component(name ${header} NAME)
    string(REGEX REPLACE "\\.h$" ".cpp" own_source ${header})
    set(checked_by_own_source FALSE)
    if(EXISTS ${own_source})
      # The first #include line; a header guard or comment before it does not matter.
      file(STRINGS ${own_source} include_lines REGEX "^#include " LIMIT_COUNT 1)
      if(include_lines MATCHES "^#include \"(${relative}|${name})\"$")
        set(checked_by_own_source TRUE)
      endif()
    endif()
    if(NOT checked_by_own_source)
      string(MAKE_C_IDENTIFIER ${relative} stem)
      set(generated ${output_dir}/${stem}.cpp)
      file(CONFIGURE OUTPUT ${generated} CONTENT "#include \"${relative}\"\n")
      list(APPEND sources ${generated})
    endif()
  endforeach()
  set(${out_var} ${sources} PARENT_SCOPE)
endfunction()
