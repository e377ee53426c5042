# cmake -DBUILD_DIR=... -DPREFIX=... -P install_prefix.cmake: installs the
# build into a fresh prefix, so that nothing of an earlier install is tested.
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} --prefix ${PREFIX} failed: ${result}")
endif()
foreach(file bin/gearimpact lib/libgearimpact.a include/gearimpact/gearimpact.hpp
    lib/cmake/gearimpact/gearimpactConfig.cmake lib/cmake/gearimpact/gearimpactConfigVersion.cmake
    lib/pkgconfig/gearimpact.pc share/gearimpact/paper_data/dynamics_statements.csv)
  if(NOT EXISTS ${PREFIX}/${file})
    message(FATAL_ERROR "the install has no ${file} in ${PREFIX}")
  endif()
endforeach()
