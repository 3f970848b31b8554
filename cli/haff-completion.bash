# bash completion for haff (installed by `make install` as
# PREFIX/share/bash-completion/completions/haff).  It asks the binary itself, so it cannot drift:
# the subcommands are the block "commands:" of `haff --help`, a subcommand's programs the block
# "programs:" of `haff CMD --help` (haff mc) and its first words the block "formats:" (haff
# export), its options the --long options of its help's option lines (those that begin with
# "  --NAME" or "  -X, --NAME": an option named in the prose, as sweep's "axes of --set
# overrides", is not one of its own), and the value of --set the scene keys of
# `haff run --list-keys` (SECTION.KEY=; for a [species NAME] key, the NAMEs of the scene files
# on the line, and for its alpha_OTHER and beta_OTHER the other species).  Files are completed
# otherwise.

# The names of a help text's block that starts with the line "$2:".
_haff_block() {
  awk -v h="$2:" '$0 == h {f = 1; next} f && /^$/ {f = 0} f && /^  [^ ]/ {print $1}' <<<"$1"
}

# The --long options of a help text's option lines.
_haff_options() {
  grep -E -- '^  (-[[:alnum:]], )?--[[:alnum:]]' <<<"$1" |
    sed -E 's/^  (-[[:alnum:]], )?(--[[:alnum:]][[:alnum:]-]*).*/\2/' | sort -u
}

# The scene keys for --set: `haff run --list-keys`, each "species.NAME.KEY" once per [species
# NAME] section of the scene files (*.ini) on the command line (left as NAME without one).
_haff_keys() {
  local haff=$1 keys names w
  keys=$("$haff" run --list-keys 2>/dev/null) || return 0
  for w in "${COMP_WORDS[@]}"; do
    [[ $w == *.ini && -r $w ]] || continue
    names+=" $(sed -nE 's/^[[:space:]]*\[species[[:space:]]+([[:alnum:]_]+)[[:space:]]*\].*/\1/p' "$w")"
  done
  if [ -n "${names// /}" ]; then
    local k n
    for k in $keys; do
      if [[ $k == species.NAME.*_OTHER ]]; then
        local kind=${k#species.NAME.}
        kind=${kind%_OTHER}
        for n in $names; do
          for o in $names dimers disks; do [ "$o" != "$n" ] && echo "species.$n.${kind}_$o"; done
        done
      elif [[ $k == species.NAME.* ]]; then
        for n in $names; do echo "species.$n.${k#species.NAME.}"; done
      else
        echo "$k"
      fi
    done
  else
    printf '%s\n' "$keys"
  fi
}

_haff() {
  local cur=${COMP_WORDS[COMP_CWORD]} haff=${COMP_WORDS[0]} help words
  local prev=${COMP_WORDS[COMP_CWORD - 1]}
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
    [[ $cur == -* ]] || words+=" $(_haff_block "$help" formats)"
    if [ -n "${words// /}" ]; then
      mapfile -t COMPREPLY < <(compgen -W "$words" -- "$cur")
      return 0
    fi
  elif [ -n "$(_haff_block "$help" programs)" ]; then
    help=$("$haff" "$cmd" "${COMP_WORDS[2]}" --help 2>/dev/null) || return 0
  fi
  if [ "$prev" = "--set" ] && grep -qE -- '^  --set ' <<<"$help"; then
    words=$(_haff_keys "$haff" | sed 's/$/=/')
    mapfile -t COMPREPLY < <(compgen -W "$words" -- "$cur")
    [ ${#COMPREPLY[@]} -gt 0 ] && compopt -o nospace 2>/dev/null
    return 0
  fi
  if [[ $cur == -* ]]; then
    words=$(_haff_options "$help")
    mapfile -t COMPREPLY < <(compgen -W "$words --help" -- "$cur")
    return 0
  fi
  mapfile -t COMPREPLY < <(compgen -f -- "$cur")
  return 0
}
complete -o filenames -o bashdefault -F _haff haff
