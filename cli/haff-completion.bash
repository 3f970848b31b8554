# bash completion for haff (installed by `make install` as
# PREFIX/share/bash-completion/completions/haff).  It asks the binary itself, so it cannot drift:
# the subcommands are the block "commands:" of `haff --help`, a subcommand's programs the block
# "programs:" of `haff CMD --help` (haff mc), and its options every --long option its help shows.
# Files are completed otherwise.

# The names of a help text's block that starts with the line "$2:".
_haff_block() {
  awk -v h="$2:" '$0 == h {f = 1; next} f && /^$/ {f = 0} f && /^  [^ ]/ {print $1}' <<<"$1"
}

_haff() {
  local cur=${COMP_WORDS[COMP_CWORD]} haff=${COMP_WORDS[0]} help words
  COMPREPLY=()
  if [ "$COMP_CWORD" -eq 1 ]; then
    words="$(_haff_block "$("$haff" --help 2>/dev/null)" commands) --help --version -V"
    mapfile -t COMPREPLY < <(compgen -W "$words" -- "$cur")
    return 0
  fi
  local cmd=${COMP_WORDS[1]}
  help=$("$haff" "$cmd" --help 2>/dev/null) || return 0
  if [ "$COMP_CWORD" -eq 2 ]; then
    words=$(_haff_block "$help" programs)
    if [ -n "$words" ]; then
      mapfile -t COMPREPLY < <(compgen -W "$words" -- "$cur")
      return 0
    fi
  elif [ -n "$(_haff_block "$help" programs)" ]; then
    help=$("$haff" "$cmd" "${COMP_WORDS[2]}" --help 2>/dev/null) || return 0
  fi
  if [[ $cur == -* ]]; then
    words=$(grep -oE -- '(^|[^[:alnum:]-])--[[:alnum:]][[:alnum:]-]*' <<<"$help" |
            sed 's/^[^-]*//' | sort -u)
    mapfile -t COMPREPLY < <(compgen -W "$words --help" -- "$cur")
    return 0
  fi
  mapfile -t COMPREPLY < <(compgen -f -- "$cur")
  return 0
}
complete -o filenames -o bashdefault -F _haff haff
