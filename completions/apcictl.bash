# SPDX-License-Identifier: MIT
# bash completion of apcictl (docs/apcictl.md, "Shell completion"), installed as
# share/bash-completion/completions/apcictl. The candidates come from apcictl itself
# (`apcictl __complete WORDS...`: its command table, each command's options, the object
# names), so this script never drifts from the program.
_apcictl() {
    local line=${COMP_LINE:0:COMP_POINT}
    local -a words
    # The words as apcictl sees them (split at blanks only; bash's own words also break at
    # ':' and '=', so a URI or an object name may be several of them).
    read -r -a words <<< "$line"
    [[ $line == *[[:blank:]] || ${#words[@]} -eq 0 ]] && words+=("")
    local typed=${words[-1]}
    local candidates
    candidates=$("${words[0]}" __complete "${words[@]:1}" 2>/dev/null) || return 0
    if [[ $candidates == ":files" ]]; then
        compopt -o default 2>/dev/null
        COMPREPLY=()
        return 0
    fi
    # bash replaces only its own current word: cut what lies before it off each candidate.
    local current=${COMP_WORDS[COMP_CWORD]}
    [[ $current == [:=] ]] && current=""
    local cut=$(( ${#typed} - ${#current} ))
    local candidate
    COMPREPLY=()
    while IFS= read -r candidate; do
        [[ -n $candidate ]] && COMPREPLY+=("${candidate:cut}")
    done <<< "$candidates"
    # A name cut after a part (tc., tc.group[) goes on: no blank after it.
    if [[ ${#COMPREPLY[@]} -eq 1 && ${COMPREPLY[0]} == *[.[] ]]; then
        compopt -o nospace 2>/dev/null
    fi
    return 0
}
complete -F _apcictl apcictl
