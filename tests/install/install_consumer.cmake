# Run by CTest (tests/install/CMakeLists.txt) with HRAD_SOURCE_DIR, HRAD_BINARY_DIR, WORK_DIR, CXX and
# LAUNCHER (the build's compiler launcher, e.g. ccache, its items joined by '|'; may be empty):
# installs hrad into WORK_DIR/prefix, builds consumer/ against it and runs it. Fails at the first step
# that fails, and when the consumer's compile line shows hrad's trees or a private dependency's flags.
set(consumer_dir ${CMAKE_CURRENT_LIST_DIR}/consumer)
string(REPLACE "|" ";" launcher "${LAUNCHER}")
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${HRAD_BINARY_DIR} --prefix ${WORK_DIR}/prefix
                OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
foreach(file include/hrad/version.h include/hrad/core/types.h lib/cmake/hrad/hradConfig.cmake
             lib/cmake/hrad/hradConfigVersion.cmake)
  if(NOT EXISTS ${WORK_DIR}/prefix/${file})
    message(FATAL_ERROR "cmake --install did not write ${file}")
  endif()
endforeach()

execute_process(COMMAND ${CMAKE_COMMAND} -S ${consumer_dir} -B ${WORK_DIR}/build -DCMAKE_BUILD_TYPE=Release
                        -DCMAKE_CXX_COMPILER=${CXX} "-DCMAKE_CXX_COMPILER_LAUNCHER=${launcher}" -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
                OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)

# The consumer compiles against the prefix only, and no private dependency reaches its compile line:
# CGAL's -frounding-math and definitions, fmt's definitions (hrad's headers need only Eigen and
# nlohmann_json).
file(READ ${WORK_DIR}/build/compile_commands.json commands)
foreach(needle "${HRAD_SOURCE_DIR}/lib" "${HRAD_BINARY_DIR}/include" "-frounding-math" "CGAL_" "FMT_")
  string(FIND "${commands}" "${needle}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the consumer's compile line contains '${needle}':\n${commands}")
  endif()
endforeach()

execute_process(COMMAND ${WORK_DIR}/build/consumer ${consumer_dir}/box.obj COMMAND_ERROR_IS_FATAL ANY)
