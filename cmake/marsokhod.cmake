# marsokhod_library(NAME SOURCES ... DEPS ...): one CMake library per layer; headers are
# included as "core/<layer>/<file>.hpp" from src/.
function(marsokhod_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS} PRIVATE marsokhod_warnings)
endfunction()

# marsokhod_test(NAME SOURCES ... DEPS ...): a GoogleTest program whose cases ctest sees one by one.
function(marsokhod_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} marsokhod_test_main marsokhod_warnings)
  target_compile_definitions(${name} PRIVATE
    MARSOKHOD_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
    PROPERTIES ENVIRONMENT "MARSOKHOD_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
