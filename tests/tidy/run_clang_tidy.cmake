# Runs clang-tidy (checks: SOURCE_DIR/.clang-tidy) over the project's non-test sources, JOBS files
# at a time (run-clang-tidy), with the compile commands of BUILD_DIR. Fails listing every finding.
# Reproduce one file: clang-tidy -p build core/pps/src/taxel_map.cpp
#
# Which sources (environment variable SOMASIM_TIDY_SCOPE):
#   all (default)  every one of them (~25 CPU-min on the CI machine);
#   slice          a bounded slice for CI: the sources changed in the last SOMASIM_TIDY_RECENT
#                  commits (default 15) or not yet committed, those that include a changed header
#                  by name, and one source in four in turn (which quarter: the commit count modulo
#                  4), so that consecutive CI runs cover every source.
set(db ${BUILD_DIR}/compile_commands.json)
if(NOT EXISTS ${db})
  message(FATAL_ERROR "${db} missing: configure with -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "
                      "(the top-level CMakeLists.txt sets it) and a Ninja or Makefile generator")
endif()
if(NOT EXISTS ${SOURCE_DIR}/.clang-tidy)
  message(FATAL_ERROR "${SOURCE_DIR}/.clang-tidy missing")
endif()

# The sources checked: every library, plugin and app source (tests, tools and benchmarks are not).
file(GLOB files ${SOURCE_DIR}/core/*/src/*.cpp ${SOURCE_DIR}/plugins/*/*.cpp ${SOURCE_DIR}/app/*.cpp)
list(SORT files)
set(scope "$ENV{SOMASIM_TIDY_SCOPE}")
if(scope STREQUAL "")
  set(scope all)
endif()
if(scope STREQUAL "slice")
  include(${CMAKE_CURRENT_LIST_DIR}/tidy_slice.cmake)
  tidy_slice(files "${SOURCE_DIR}" "${files}")
elseif(NOT scope STREQUAL "all")
  message(FATAL_ERROR "SOMASIM_TIDY_SCOPE='${scope}': expected 'all' or 'slice'")
endif()
list(LENGTH files n_files)
# run-clang-tidy takes the files as regular expressions on the database's paths: one alternative
# per file, each escaped.
set(pattern "")
foreach(f ${files})
  string(REGEX REPLACE "([][.+*?()^$|\\\\{}])" "\\\\\\1" escaped "${f}")
  list(APPEND pattern "${escaped}")
endforeach()
string(REPLACE ";" "|" pattern "${pattern}")
set(pattern "^(${pattern})$")
# Each of them must be compiled by the build (else it would silently go unchecked).
file(READ ${db} db_text)
set(missing "")
foreach(f ${files})
  string(FIND "${db_text}" "\"file\": \"${f}\"" at)
  if(at EQUAL -1)
    list(APPEND missing ${f})
  endif()
endforeach()
if(missing)
  string(REPLACE ";" "\n  " missing "${missing}")
  message(FATAL_ERROR "not in ${db} (not compiled by any target?):\n  ${missing}")
endif()

if(NOT JOBS OR JOBS LESS 1)
  set(JOBS 2)
endif()
message(STATUS "clang-tidy on ${n_files} files (scope: ${scope}), ${JOBS} at a time")
# -Wno-error: the build's -Werror (CI) must not turn the compiler warnings clang sees with GCC's
# flags into clang-tidy errors; the checks of .clang-tidy decide what is a finding.
execute_process(
  COMMAND ${RUN_CLANG_TIDY} -clang-tidy-binary ${CLANG_TIDY} -p ${BUILD_DIR} -j ${JOBS} -quiet
          -extra-arg=-Wno-error ${pattern}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
# run-clang-tidy 14 always asks clang-tidy for colours: drop the escape sequences.
string(ASCII 27 esc)
string(REGEX REPLACE "${esc}\\[[0-9;]*m" "" out "${out}")
string(REGEX REPLACE "${esc}\\[[0-9;]*m" "" err "${err}")

# run-clang-tidy prints the command line of every file it ran: all of them must have run.
string(REGEX MATCHALL "[^\n]*-p=[^\n]*\\.cpp\n" runs "${out}")
list(LENGTH runs n_runs)
# Any diagnostic of a check ("file:line:col: warning|error: text [check-name]") is a finding; so
# is a compile error (clang-diagnostic-error: the file does not compile as the build says).
# (Messages contain ';', the CMake list separator: swapped for \x01 while they are list items.)
string(ASCII 1 sep)
string(REPLACE ";" "${sep}" all "${out}${err}")
string(REGEX MATCHALL "[^\n]*: (warning|error): [^\n]*\\[[a-z][^\n]*\\]\n" findings "${all}")
list(REMOVE_DUPLICATES findings)  # a header's finding is reported by every file including it
list(LENGTH findings n_findings)
if(NOT rc EQUAL 0 OR n_findings GREATER 0 OR NOT n_runs EQUAL n_files)
  message("${out}")
  message("${err}")
  string(REPLACE "\n;" "\n" findings "${findings}")
  string(REPLACE "${sep}" ";" findings "${findings}")
  message("== findings (each once):\n${findings}")
  message(FATAL_ERROR "clang-tidy: ${n_findings} finding(s), ${n_runs} of ${n_files} files run, "
                      "exit code ${rc}. Fix them (checks and reasons: .clang-tidy); for a false "
                      "positive, say why beside a // NOLINT(check-name) comment.")
endif()
message(STATUS "clang-tidy: ${n_files} files clean")
