# hrad_module(NAME DEPS ...): a static library hrad_NAME from lib/hrad/NAME/*.cpp.
# Each module owns its lib/hrad/NAME/CMakeLists.txt, so modules build and test on their own.
function(hrad_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  if(sources)
    add_library(hrad_${name} STATIC ${sources})
    target_include_directories(hrad_${name} PUBLIC ${PROJECT_SOURCE_DIR}/lib)
    target_link_libraries(hrad_${name} PUBLIC ${ARG_DEPS})
    target_compile_options(hrad_${name} PRIVATE -Wall -Wextra)
  else()
    add_library(hrad_${name} INTERFACE)
    target_include_directories(hrad_${name} INTERFACE ${PROJECT_SOURCE_DIR}/lib)
    target_link_libraries(hrad_${name} INTERFACE ${ARG_DEPS})
  endif()
  add_library(hrad::${name} ALIAS hrad_${name})
endfunction()

# hrad_test(NAME DEPS ... [LABELS ...]): one GoogleTest executable NAME_test from the
# *_test.cpp files of the calling folder, registered with CTest, labelled `unit`, or by LABELS
# instead when given. gtest_discover_tests does not carry a list through its PROPERTIES, so with
# several labels a script run after the discovered tests' own sets them all.
function(hrad_test name)
  cmake_parse_arguments(ARG "" "" "DEPS;LABELS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cpp)
  add_executable(${name}_test ${sources})
  target_link_libraries(${name}_test PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name}_test PRIVATE
    HRAD_SOURCE_DIR="${PROJECT_SOURCE_DIR}" HRAD_BINARY_DIR="${PROJECT_BINARY_DIR}")
  set(labels unit)
  if(ARG_LABELS)
    set(labels ${ARG_LABELS})
  endif()
  list(GET labels 0 first_label)
  gtest_discover_tests(${name}_test
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES LABELS "${first_label}"
    DISCOVERY_TIMEOUT 60)
  list(LENGTH labels label_count)
  if(label_count GREATER 1)
    set(script ${CMAKE_CURRENT_BINARY_DIR}/${name}_test_labels.cmake)
    file(WRITE ${script} "if(${name}_test_TESTS)\n  set_tests_properties(\${${name}_test_TESTS} PROPERTIES LABELS \"${labels}\")\nendif()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${script})
  endif()
endfunction()
