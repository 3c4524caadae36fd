# ctest toolchain.constant_stores_every_tuning: compiles constant_store_probe.cpp
# with the project's code generation options and each -mtune the compiler
# knows, runs it, and fails naming every tuning whose build stores the wrong
# constant. The -march stays the project's (or x86-64-v3 where this CPU has
# AVX2), so every build runs here whatever CPU it is tuned for.
# Inputs: CXX, OPTIONS (a ;-list), SOURCE, WORK_DIR.
file(MAKE_DIRECTORY ${WORK_DIR})
execute_process(COMMAND ${CXX} -Q --help=target OUTPUT_VARIABLE help RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${CXX} -Q --help=target failed: cannot list the tunings")
endif()
string(REGEX MATCH "Known valid arguments for -mtune= option:\n[ \t]*([^\n]*)" _ "${help}")
string(REPLACE " " ";" tunings "${CMAKE_MATCH_1}")
list(REMOVE_ITEM tunings "")
list(LENGTH tunings tuning_count)
if(tuning_count LESS 5)
  message(FATAL_ERROR "could not read the -mtune list from ${CXX} -Q --help=target")
endif()

# Instruction sets to try: the project's own, and AVX2 (x86-64-v3) when this
# CPU runs it and the project's options do not already ask for more.
set(arch_variants "project")
execute_process(COMMAND grep -qw avx2 /proc/cpuinfo RESULT_VARIABLE no_avx2)
if(no_avx2 EQUAL 0)
  list(APPEND arch_variants "x86-64-v3")
endif()

set(failures)
set(builds 0)
foreach(arch ${arch_variants})
  set(options ${OPTIONS})
  if(NOT arch STREQUAL "project")
    list(FILTER options EXCLUDE REGEX "^-march=|^-mno-avx512f$")
    list(APPEND options -march=${arch})
  endif()
  foreach(tuning ${tunings})
    set(program ${WORK_DIR}/probe_${arch}_${tuning})
    execute_process(COMMAND ${CXX} -std=c++20 -O2 ${options} -mtune=${tuning} ${SOURCE} -o ${program}
                    RESULT_VARIABLE compiled ERROR_VARIABLE compile_errors)
    if(NOT compiled EQUAL 0)
      # A tuning this compiler lists but refuses with these options (32-bit
      # only CPUs under -m64) is not a build anyone can make.
      continue()
    endif()
    math(EXPR builds "${builds} + 1")
    execute_process(COMMAND ${program} RESULT_VARIABLE ran OUTPUT_VARIABLE said)
    if(NOT ran EQUAL 0)
      string(STRIP "${said}" said)
      list(APPEND failures "  -march=${arch} -mtune=${tuning}: ${said}")
    endif()
  endforeach()
endforeach()

string(REPLACE ";" " " shown "${OPTIONS}")
if(builds LESS 10)
  message(FATAL_ERROR "only ${builds} probe builds compiled with ${shown}: the check checked nothing")
endif()
if(failures)
  string(REPLACE ";" "\n" listed "${failures}")
  message(FATAL_ERROR "the compiler stores a wrong constant with the project's options (${shown}) under:\n${listed}")
endif()
message(STATUS "constant stores correct in all ${builds} probe builds (${arch_variants} x ${tuning_count} tunings), options ${shown}")
