// The scripts a `filmback submit` job folder holds, from core/cmd/slurm/*.sh (embedded at build
// time by core/cmd/slurm/embed_scripts.cmake).
#pragma once

namespace fb {

extern const char* const kTileTaskScript;   // core/cmd/slurm/tile_task.sh
extern const char* const kMergeTaskScript;  // core/cmd/slurm/merge_task.sh

}  // namespace fb
