# mixmesh_module(NAME [DEPENDS module...] [LIBRARIES target...] [INCLUDES dir...])
#
# One static library per stage folder src/NAME (skipped while the folder does not
# exist), so a test links only the stages it exercises.
set(mixmesh_modules "")

function(mixmesh_module name)
  cmake_parse_arguments(PARSE_ARGV 1 module "" "" "DEPENDS;LIBRARIES;INCLUDES")
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${name}/*.cpp)
  if(NOT sources)
    return()
  endif()
  set(target mixmesh_${name})
  add_library(${target} STATIC ${sources})
  add_library(mixmesh::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                              $<INSTALL_INTERFACE:include>)
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/src ${module_INCLUDES})
  target_compile_options(${target} PRIVATE ${mixmesh_warnings})
  foreach(dependency IN LISTS module_DEPENDS)
    if(TARGET mixmesh_${dependency})
      target_link_libraries(${target} PUBLIC mixmesh_${dependency})
    endif()
  endforeach()
  target_link_libraries(${target} PUBLIC ${module_LIBRARIES})
  set(mixmesh_modules ${mixmesh_modules} ${target} PARENT_SCOPE)
endfunction()
