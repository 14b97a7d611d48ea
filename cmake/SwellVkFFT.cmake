# The VkFFT anchor (bench/vkfft_anchor.cpp): Debian's header-only VkFFT (libvkfft-dev 1.2.26),
# the reference the swell Vulkan backend is measured against. Never fails the configure: sets
# SWELL_VKFFT_AVAILABLE, and SWELL_VKFFT_REASON when it is OFF; when ON, the INTERFACE target
# swell_vkfft carries the patched header, VKFFT_BACKEND=0 (Vulkan) and glslang.
#
# Why a patch: glslang 12 inserted nine mesh-shader fields (max_mesh_output_vertices_ext …
# max_mesh_view_count_ext) before max_dual_source_draw_buffers_ext in glslang_resource_t. VkFFT
# 1.2.26 fills that struct positionally (twice), so its dual-source value and its braced .limits
# initializer land in the new int fields: it does not compile. VkFFT 1.2.30 assigns by name; here
# the nine values (glslang's own DefaultTBuiltInResource) are inserted before the dual-source
# value, in a copy of the header in the build tree. The original is never modified, and no copy
# is committed.

function(swell_configure_vkfft)
  set(SWELL_VKFFT_AVAILABLE OFF PARENT_SCOPE)
  find_file(SWELL_VKFFT_HEADER vkFFT.h)
  find_file(SWELL_GLSLANG_C_INTERFACE glslang/Include/glslang_c_interface.h)
  if(NOT SWELL_VKFFT_HEADER OR NOT SWELL_GLSLANG_C_INTERFACE)
    set(SWELL_VKFFT_REASON "vkFFT.h or glslang_c_interface.h not found (apt-get install libvkfft-dev glslang-dev)" PARENT_SCOPE)
    return()
  endif()
  # pkg-config, not find_package(glslang): Debian 12's glslang CMake config stops the configure
  # unless glslang-tools is installed (it checks for /usr/bin/glslangValidator). spirv.pc lists
  # the static libraries in a link order that works: SPIRV, SPIRV-Tools(-opt), glslang's parts.
  pkg_check_modules(SWELL_GLSLANG QUIET IMPORTED_TARGET spirv)
  if(NOT SWELL_GLSLANG_FOUND)
    set(SWELL_VKFFT_REASON "glslang's pkg-config module spirv not found (apt-get install glslang-dev spirv-tools)" PARENT_SCOPE)
    return()
  endif()
  set_property(DIRECTORY ${CMAKE_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
               ${SWELL_VKFFT_HEADER} ${SWELL_GLSLANG_C_INTERFACE})

  file(READ ${SWELL_VKFFT_HEADER} header)
  file(READ ${SWELL_GLSLANG_C_INTERFACE} glslang_api)
  string(FIND "${glslang_api}" "max_mesh_view_count_ext" glslang_has_ext_fields)
  if(glslang_has_ext_fields GREATER -1)
    set(anchor "/* .maxDualSourceDrawBuffersEXT = */")
    set(fix "/* .maxMeshOutputVerticesEXT = */ 256, /* .maxMeshOutputPrimitivesEXT = */ 256,
\t\t\t\t/* .maxMeshWorkGroupSizeX_EXT = */ 128, /* .maxMeshWorkGroupSizeY_EXT = */ 128, /* .maxMeshWorkGroupSizeZ_EXT = */ 128,
\t\t\t\t/* .maxTaskWorkGroupSizeX_EXT = */ 128, /* .maxTaskWorkGroupSizeY_EXT = */ 128, /* .maxTaskWorkGroupSizeZ_EXT = */ 128,
\t\t\t\t/* .maxMeshViewCountEXT = */ 4, /* patched by swell: cmake/SwellVkFFT.cmake */
\t\t\t\t")
    string(REPLACE "${anchor}" "${fix}${anchor}" patched "${header}")
    # Both positional initializers (the shader compile paths) must take the patch, no more.
    string(LENGTH "${header}" before)
    string(LENGTH "${patched}" after)
    string(LENGTH "${fix}" fix_length)
    math(EXPR inserted "(${after} - ${before}) / ${fix_length}")
    if(NOT inserted EQUAL 2)
      set(SWELL_VKFFT_REASON "${SWELL_VKFFT_HEADER} is not the expected VkFFT 1.2.26 text: \
the glslang 12 patch applied ${inserted} times, not 2" PARENT_SCOPE)
      return()
    endif()
  else()
    set(patched "${header}")  # glslang before 12: the positional initializer is in step
  endif()
  # Written only when different, so a reconfigure does not rebuild the anchor.
  file(WRITE ${CMAKE_BINARY_DIR}/vkfft/vkFFT.h.new "${patched}")
  file(COPY_FILE ${CMAKE_BINARY_DIR}/vkfft/vkFFT.h.new ${CMAKE_BINARY_DIR}/vkfft/vkFFT.h ONLY_IF_DIFFERENT)
  file(REMOVE ${CMAKE_BINARY_DIR}/vkfft/vkFFT.h.new)

  add_library(swell_vkfft INTERFACE)
  # SYSTEM: VkFFT's own warnings (thousands under -Wall -Wextra -Wpedantic) are not swell's.
  target_include_directories(swell_vkfft SYSTEM INTERFACE ${CMAKE_BINARY_DIR}/vkfft)
  target_compile_definitions(swell_vkfft INTERFACE VKFFT_BACKEND=0 SWELL_HAVE_VKFFT)
  target_link_libraries(swell_vkfft INTERFACE Vulkan::Vulkan PkgConfig::SWELL_GLSLANG)
  set(SWELL_VKFFT_AVAILABLE ON PARENT_SCOPE)
endfunction()

if(SWELL_WITH_VULKAN)
  swell_configure_vkfft()
else()
  set(SWELL_VKFFT_AVAILABLE OFF)
  set(SWELL_VKFFT_REASON "configured with SWELL_WITH_VULKAN=OFF")
endif()
if(SWELL_VKFFT_AVAILABLE)
  message(STATUS "swell: VkFFT anchor: ${SWELL_VKFFT_HEADER} (patched copy in ${CMAKE_BINARY_DIR}/vkfft)")
else()
  message(STATUS "swell: VkFFT anchor not built: ${SWELL_VKFFT_REASON}")
endif()
