# Sourced by the run queues (tools/show_it_runs.sh, tools/paper_convergence.sh): queue_runs TAG
# NAME... runs each NAME one after another, each in its own folder under $runs (with $bin, at nice
# $nice_level, one thread unless OMP_NUM_THREADS says otherwise), continued with --restart beside
# its checkpoint; the caller defines case_args NAME (the case file and --set arguments, or exit 2).
queue_runs() {
  local tag=$1 name line dir
  local -a args restart
  shift
  mkdir -p "$runs"
  for name in "$@"; do
    line=$(case_args "$name") || exit 2
    read -r -a args <<< "$line"
    dir=$runs/$name
    restart=()
    [ -f "$dir/checkpoint.h5" ] && restart=(--restart)
    echo "[$tag] $name -> $dir ${restart[*]}"
    OMP_NUM_THREADS=${OMP_NUM_THREADS:-1} nice -n "$nice_level" \
      "$bin" run "${args[@]}" --out "$dir" --quiet "${restart[@]}" >> "$runs/$name.log" 2>&1 ||
      echo "[$tag] $name stopped with status $? (log: $runs/$name.log)"
  done
}
