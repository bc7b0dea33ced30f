# kasha_embed_files(OUT SYMBOL [BASE DIR] FILES...) writes a C++ source defining
#   const std::vector<kasha::EmbeddedFile>& SYMBOL();
# holding each file's name (its path below DIR if given, else its file name) and contents,
# regenerated whenever a file changes.
function(kasha_embed_files out symbol)
  cmake_parse_arguments(EMBED "" "BASE" "" ${ARGN})
  set(files ${EMBED_UNPARSED_ARGUMENTS})
  string(REPLACE ";" "|" file_list "${files}")  # a ';' would split the -D argument
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DSYMBOL=${symbol} "-DFILES=${file_list}" "-DBASE=${EMBED_BASE}"
            -P ${CMAKE_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
    DEPENDS ${files} ${CMAKE_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
    COMMENT "Embedding ${symbol}"
    VERBATIM)
endfunction()
