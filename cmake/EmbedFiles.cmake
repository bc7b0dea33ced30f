# kasha_embed_files(OUT SYMBOL FILES...) writes a C++ source defining
#   const std::vector<kasha::EmbeddedFile>& SYMBOL();
# holding each file's name and contents, regenerated whenever a file changes.
function(kasha_embed_files out symbol)
  set(files ${ARGN})
  string(REPLACE ";" "|" file_list "${files}")  # a ';' would split the -D argument
  add_custom_command(
    OUTPUT ${out}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out} -DSYMBOL=${symbol} "-DFILES=${file_list}"
            -P ${CMAKE_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
    DEPENDS ${files} ${CMAKE_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
    COMMENT "Embedding ${symbol}"
    VERBATIM)
endfunction()
