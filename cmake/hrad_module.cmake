# hrad_module(NAME [DEPS ...] [PRIVATE ...]): a static library hrad_NAME (hrad::NAME) from
# lib/hrad/NAME/*.cpp. DEPS are what its headers need (PUBLIC: a user of the module compiles against
# them); PRIVATE what only its .cpp files include (linked, never compiled into a user: CGAL's
# -frounding-math, OpenMesh, libpng and the like stay inside hrad). Each module owns its
# lib/hrad/NAME/CMakeLists.txt, so modules build and test on their own. Its headers install to
# include/hrad/NAME/, the library to lib/, both into the export set `hradTargets` (lib/CMakeLists.txt).
function(hrad_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  file(GLOB headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.h)
  set(includes $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/lib> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  if(sources)
    add_library(hrad_${name} STATIC ${sources})
    target_include_directories(hrad_${name} PUBLIC ${includes})
    target_link_libraries(hrad_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE})
    target_compile_options(hrad_${name} PRIVATE -Wall -Wextra)
  else()
    if(ARG_PRIVATE)
      message(FATAL_ERROR "hrad_module(${name}): a header-only module has no PRIVATE dependencies")
    endif()
    add_library(hrad_${name} INTERFACE)
    target_include_directories(hrad_${name} INTERFACE ${includes})
    target_link_libraries(hrad_${name} INTERFACE ${ARG_DEPS})
  endif()
  set_target_properties(hrad_${name} PROPERTIES EXPORT_NAME ${name})
  add_library(hrad::${name} ALIAS hrad_${name})
  install(TARGETS hrad_${name} EXPORT hradTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hrad/${name})
  set_property(GLOBAL APPEND PROPERTY HRAD_MODULES ${name})
endfunction()

# hrad_test(NAME DEPS ... [LABELS ...]): one GoogleTest executable NAME_test from the
# *_test.cpp files of the calling folder, registered with CTest, labelled `unit`, or by LABELS
# instead when given. gtest_discover_tests does not carry a list through its PROPERTIES, so with
# several labels a script run after the discovered tests' own sets them all.
function(hrad_test name)
  cmake_parse_arguments(ARG "" "" "DEPS;LABELS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*_test.cpp)
  add_executable(${name}_test ${sources})
  target_link_libraries(${name}_test PRIVATE ${ARG_DEPS} hrad_test_paths GTest::gtest GTest::gtest_main)
  target_precompile_headers(${name}_test REUSE_FROM hrad_test_pch)  # tests/CMakeLists.txt
  # With the standard headers precompiled, GCC 12 no longer treats std::string's inlined copies as
  # system code and reports its known false positive (GCC bug 105329) in tests that build strings.
  target_compile_options(${name}_test PRIVATE $<$<CXX_COMPILER_ID:GNU>:-Wno-stringop-overflow>)
  target_compile_options(${name}_test PRIVATE ${HRAD_LIGHT_OPTIMIZATION})
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
