#!/bin/bash
# SPDX-License-Identifier: MIT
# The shells' completion of apcictl and rwmos-emu (completions/, docs/apcictl.md "Shell
# completion"), run as the shells run it, against the built programs:
#   completion_test.sh bash|zsh SOURCE_DIR BIN_DIR
# bash: the completion function with COMP_LINE, COMP_POINT and COMP_WORDS as bash sets them
# (its words also break at ':' and '='); zsh: the completion function autoloaded from the
# file, with compadd and _files standing in for the completion system's. Each check prints
# what it got; the script exits 1 at the first wrong answer.
set -u
shell=$1 source_dir=$2 bin_dir=$3
export PATH="$bin_dir:$PATH"
failures=0
check() {  # check WHAT GOT WANT
    if [[ $2 == "$3" ]]; then
        echo "ok: $1 -> $2"
    else
        echo "FAILED: $1: got '$2', want '$3'"
        failures=$((failures + 1))
    fi
}

if [[ $shell == bash ]]; then
    source "$source_dir/completions/apcictl.bash"
    complete_line() {  # the completions of LINE, cursor at its end, joined by blanks
        COMP_LINE=$1
        COMP_POINT=${#1}
        local spaced=${1//:/ : }
        spaced=${spaced//=/ = }
        read -r -a COMP_WORDS <<< "$spaced"
        [[ $1 == *' ' ]] && COMP_WORDS+=("")
        COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
        COMPREPLY=()
        _apcictl apcictl
        echo "${COMPREPLY[*]}"
    }
    check "apcictl re" "$(complete_line 'apcictl re')" "read"
    check "apcictl s" "$(complete_line 'apcictl s')" "script shell status spool ssf step"
    check "apcictl he" "$(complete_line 'apcictl he')" "help"
    check "apcictl help wr" "$(complete_line 'apcictl help wr')" "write"
    check "apcictl read tc.gr" "$(complete_line 'apcictl read tc.gr')" "tc.group["
    check "apcictl read tc.group[2].rad" "$(complete_line 'apcictl read tc.group[2].rad')" \
        "tc.group[2].radius"
    check "apcictl write tc.group[2].radius 2" "$(complete_line 'apcictl write tc.group[2].radius 2')" ""
    check "apcictl run --to" "$(complete_line 'apcictl run --to')" "--tools --tools-out"
    check "apcictl --device emu" "$(complete_line 'apcictl --device emu')" "emu: emu:?no-option-tc"
    # bash's word after the ':' is "?no": only the rest of the URI replaces it.
    check "apcictl --device emu:?no" "$(complete_line 'apcictl --device emu:?no')" "?no-option-tc"
    check "apcictl -d emu: stat" "$(complete_line 'apcictl -d emu: stat')" "status"
    check "apcictl run (a file)" "$(complete_line 'apcictl run ')" ""
    check "apcictl frobnicate x" "$(complete_line 'apcictl frobnicate x')" ""
    # rwmos-emu: its --help's options, through bash-completion's _longopt.
    if [[ -f /usr/share/bash-completion/bash_completion ]]; then
        source /usr/share/bash-completion/bash_completion
        source "$source_dir/completions/rwmos-emu.bash"
        COMP_LINE="rwmos-emu --so" COMP_POINT=14 COMP_WORDS=(rwmos-emu --so) COMP_CWORD=1
        COMPREPLY=()
        _longopt rwmos-emu --so rwmos-emu
        check "rwmos-emu --so" "${COMPREPLY[*]}" "--socket"
        COMP_LINE="rwmos-emu --ver" COMP_POINT=15 COMP_WORDS=(rwmos-emu --ver) COMP_CWORD=1
        COMPREPLY=()
        _longopt rwmos-emu --ver rwmos-emu
        check "rwmos-emu --ver" "${COMPREPLY[*]}" "--version"
    else
        echo "FAILED: bash-completion is not installed (/usr/share/bash-completion/bash_completion)"
        failures=$((failures + 1))
    fi
elif [[ $shell == zsh ]]; then
    run_zsh() {  # the candidates the zsh function adds for the words WORDS..., one a line
        zsh -f -c '
            compadd() {
                local suffix=" "
                while [[ $1 == -* ]]; do
                    case $1 in
                        -S) suffix=$2; shift ;;
                        -a) shift; for w in "${(@P)1}"; do print -r -- "$w$suffix"; done ;;
                    esac
                    shift
                done
            }
            _files() { print -r -- "(files)"; }
            fpath=("$1" $fpath)
            autoload -Uz _apcictl
            shift
            words=("$@")
            CURRENT=$#words
            _apcictl
        ' zsh "$source_dir/completions" "$@" | tr '\n' '|'
    }
    check "apcictl re" "$(run_zsh apcictl re)" "read |"
    check "apcictl read tc.gr" "$(run_zsh apcictl read tc.gr)" "tc.group[|"
    check "apcictl read tc.group[1].rad" "$(run_zsh apcictl read 'tc.group[1].rad')" \
        "tc.group[1].radius |"
    check "apcictl run --tools" "$(run_zsh apcictl run --tools '')" "(files)|"
    check "apcictl --device e" "$(run_zsh apcictl --device e)" "emu: |emu:?no-option-tc |"
    check "apcictl help sh" "$(run_zsh apcictl help sh)" "shell |"
else
    echo "usage: completion_test.sh bash|zsh SOURCE_DIR BIN_DIR" >&2
    exit 2
fi
echo "$failures failed"
[[ $failures == 0 ]]
