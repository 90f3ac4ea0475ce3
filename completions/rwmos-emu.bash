# SPDX-License-Identifier: MIT
# bash completion of rwmos-emu, installed as share/bash-completion/completions/rwmos-emu: its
# options as its own --help lists them (bash-completion's _longopt), file names for the paths.
complete -F _longopt rwmos-emu
