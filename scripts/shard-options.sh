# Sourced by the scripts that run a sweep or a data set in shards (parallel-*.sh, slurm/submit-*.sh):
# their common options, read and checked one way. The sourcing script sets
#   tool     its name in messages, e.g. parallel-sweep
#   options  the options it takes beyond --shards, --out and --gearimpact: "--jobs", "--throttle"
#   usage    a function that prints its usage and exits 2
#   gearimpact, jobs, throttle  their defaults
# and then reads them and drops what was read, leaving the command's own arguments:
#   shard_options_read "$@"; shift "$shard_options_used"
# After it: shards, out, gearimpact (an absolute path to an executable), jobs, throttle.

shard_options_count() {  # shard_options_count OPTION VALUE [optional]: an integer >= 1
  if [[ -n "${3-}" && -z "$2" ]]; then return 0; fi
  if [[ ! "$2" =~ ^[1-9][0-9]*$ ]]; then
    echo "$tool: $1 must be an integer >= 1, got '$2'" >&2
    usage
  fi
}

shard_options_read() {
  shards="" out="" shard_options_used=0
  while (($#)); do
    case "$1" in
      --shards) shards="${2-}" ;;
      --out) out="${2-}" ;;
      --gearimpact) gearimpact="${2-}" ;;
      --jobs | --throttle)
        [[ " $options " == *" $1 "* ]] || break
        if [[ "$1" == --jobs ]]; then jobs="${2-}"; else throttle="${2-}"; fi
        ;;
      --) shift; shard_options_used=$((shard_options_used + 1)); break ;;
      *) break ;;
    esac
    (($# >= 2)) || usage
    shift 2
    shard_options_used=$((shard_options_used + 2))
  done
  shard_options_count --shards "$shards"
  if [[ " $options " == *" --jobs "* ]]; then shard_options_count --jobs "$jobs"; fi
  if [[ " $options " == *" --throttle "* ]]; then shard_options_count --throttle "$throttle" optional; fi
  [[ -n "$out" ]] || usage
  (($#)) || usage
  # The jobs get an absolute path: they may start on another node, in another folder, or after
  # the caller has moved on.
  local given="$gearimpact"
  if [[ "$gearimpact" == */* ]]; then
    gearimpact="$(cd "$(dirname "$gearimpact")" 2>/dev/null && pwd -P)/$(basename "$gearimpact")"
  else
    gearimpact="$(type -P "$gearimpact" || true)"
  fi
  if [[ ! -x "$gearimpact" ]]; then
    echo "$tool: --gearimpact '$given' is not an executable program" >&2
    exit 2
  fi
}
