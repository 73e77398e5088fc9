# craterkit_add_library(NAME <short> [DEPS <targets...>] [PRIVATE_DEPS <targets...>])
# A library target craterkit_<short> with the alias craterkit::<short>, sources globbed from src/ of the
# calling directory, public headers in include/craterkit/<...>, installed and exported. DEPS are what the
# public headers use (a consumer sees them); PRIVATE_DEPS only what the sources use.
function(craterkit_add_library)
  cmake_parse_arguments(ARG "" "NAME" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB_RECURSE _sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  if(NOT _sources)
    message(FATAL_ERROR "craterkit_${ARG_NAME}: no sources in ${CMAKE_CURRENT_SOURCE_DIR}/src")
  endif()
  add_library(craterkit_${ARG_NAME} ${_sources})
  add_library(craterkit::${ARG_NAME} ALIAS craterkit_${ARG_NAME})
  set_target_properties(craterkit_${ARG_NAME} PROPERTIES EXPORT_NAME ${ARG_NAME} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(craterkit_${ARG_NAME} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                                          $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(craterkit_${ARG_NAME} PUBLIC cxx_std_20)
  target_link_libraries(craterkit_${ARG_NAME} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS} $<BUILD_INTERFACE:craterkit_warnings>)
  install(TARGETS craterkit_${ARG_NAME} EXPORT craterkitTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
