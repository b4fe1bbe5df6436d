# Writes OUTPUT: a C++ file that holds the task scripts of `filmback submit` (tile_task.sh,
# merge_task.sh, beside this file) as raw strings, so that the executable writes them into each job
# folder without looking for installed files. Run by core/cmd/CMakeLists.txt at build time.
set(_text "// Generated from core/cmd/slurm/*.sh by embed_scripts.cmake.\n")
string(APPEND _text "#include \"core/cmd/slurm_scripts.h\"\n\nnamespace fb {\n\n")
macro(embed_script _script _constant)
  file(READ ${CMAKE_CURRENT_LIST_DIR}/${_script}.sh _body)
  string(FIND "${_body}" ")fbscript\"" _clash)
  if(NOT _clash EQUAL -1)
    message(FATAL_ERROR "${_script}.sh holds the raw string's delimiter")
  endif()
  string(APPEND _text "extern const char* const ${_constant} = R\"fbscript(${_body})fbscript\";\n\n")
endmacro()
embed_script(tile_task kTileTaskScript)
embed_script(merge_task kMergeTaskScript)
string(APPEND _text "}  // namespace fb\n")
file(WRITE ${OUTPUT}.tmp "${_text}")
file(RENAME ${OUTPUT}.tmp ${OUTPUT})
