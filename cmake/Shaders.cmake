# rayglass_add_shaders(target dir): compile every GLSL stage file in `dir` to
# bin/shaders/<dir name>/<file>.spv for Vulkan 1.2 / SPIR-V 1.4 (the lowest
# version ray tracing stages need). glslangValidator writes a depfile, so
# editing an #included file (shaders/common/*.glsl, shared/host_device.h)
# rebuilds exactly the shaders that include it.
function(rayglass_add_shaders target dir)
  get_filename_component(name ${dir} NAME)
  file(GLOB stages ${dir}/*.comp ${dir}/*.rgen ${dir}/*.rmiss ${dir}/*.rchit
                   ${dir}/*.rahit ${dir}/*.rint)
  set(outputs "")
  foreach(src IN LISTS stages)
    get_filename_component(file ${src} NAME)
    set(spv ${RG_BIN_DIR}/shaders/${name}/${file}.spv)
    set(dep ${CMAKE_BINARY_DIR}/shaderdeps/${name}/${file}.d)
    add_custom_command(
      OUTPUT ${spv}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${RG_BIN_DIR}/shaders/${name}
              ${CMAKE_BINARY_DIR}/shaderdeps/${name}
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.2 --target-env spirv1.4
              -I${CMAKE_SOURCE_DIR}/shaders/common -I${CMAKE_SOURCE_DIR}/shared
              --depfile ${dep} -o ${spv} ${src}
      DEPENDS ${src}
      DEPFILE ${dep}
      COMMENT "GLSL ${name}/${file}"
      VERBATIM)
    list(APPEND outputs ${spv})
  endforeach()
  add_custom_target(${target}_shaders DEPENDS ${outputs})
  add_dependencies(${target} ${target}_shaders)
endfunction()
