# discreel_embed(<target> NAMESPACE <ns> FILES <file>...)
# Compiles each file into <target> as a `std::string_view <ns>::<identifier>` so that the
# binary needs nothing from the source tree at run time (shaders, the built-in demo scene).
# The identifier is the file name with every non-alphanumeric character replaced by '_'
# (shaders/disc.frag -> disc_frag). Declarations go to <binary dir>/embedded/<ns>.hpp.
set(_DISCREEL_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/EmbedFiles.cmake)

function(discreel_embed target)
  cmake_parse_arguments(ARG "" "NAMESPACE" "FILES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/embedded)
  set(out_cpp ${out_dir}/${ARG_NAMESPACE}.cpp)
  set(out_hpp ${out_dir}/${ARG_NAMESPACE}.hpp)
  set(abs_files "")
  foreach(f IN LISTS ARG_FILES)
    get_filename_component(abs ${f} ABSOLUTE)
    list(APPEND abs_files ${abs})
  endforeach()
  string(REPLACE ";" "|" files_arg "${abs_files}")
  add_custom_command(
    OUTPUT ${out_cpp} ${out_hpp}
    COMMAND ${CMAKE_COMMAND} -DNAMESPACE=${ARG_NAMESPACE} "-DFILES=${files_arg}"
            -DOUT_CPP=${out_cpp} -DOUT_HPP=${out_hpp} -P ${_DISCREEL_EMBED_SCRIPT}
    DEPENDS ${abs_files} ${_DISCREEL_EMBED_SCRIPT}
    COMMENT "Embedding ${ARG_NAMESPACE}"
    VERBATIM)
  target_sources(${target} PRIVATE ${out_cpp} ${out_hpp})
  target_include_directories(${target} PRIVATE ${out_dir})
endfunction()
