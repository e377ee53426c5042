// `--shard K/N` of the commands that split their work over processes (sweep, dataset): 0 <= K < N,
// or from a Slurm job array's SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN of SLURM_ARRAY_TASK_COUNT.
#pragma once

#include <string>

namespace gearimpact::cli {

struct ShardFlag {
  int k = 0;
  int n = 1;
};

// `given`: the flag was on the command line (an empty text is then refused); without it, Slurm's
// variables, else the whole (0/1). Throws InputError naming --shard or the variable.
ShardFlag parse_shard_flag(const std::string& text, bool given);

}  // namespace gearimpact::cli
