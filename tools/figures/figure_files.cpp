// SPDX-License-Identifier: MIT
#include "figure_files.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

namespace figure_files {
namespace {

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int write_figures(int argc, char** argv, std::string_view program,
                  const std::vector<FigureFile>& figures) {
    const std::string name(program);
    const bool check = argc == 3 && std::string(argv[1]) == "--check";
    if (argc != 2 && !check) {
        std::fprintf(stderr, "usage: %s [--check] DIR\n", name.c_str());
        return 2;
    }
    const std::string dir = argv[argc - 1];
    int status = 0;
    for (const FigureFile& f : figures) {
        const std::string path = dir + "/" + f.name + ".svg";
        const std::string svg = f.draw();
        if (check) {
            if (read_file(path) != svg) {
                std::fprintf(stderr, "%s is not what tools/figures/%s.cpp draws: run %s %s\n",
                             path.c_str(), name.c_str(), name.c_str(), dir.c_str());
                status = 1;
            }
            continue;
        }
        std::ofstream out(path, std::ios::binary);
        out << svg;
        if (!out) {
            std::fprintf(stderr, "%s: cannot write\n", path.c_str());
            return 1;
        }
    }
    return status;
}

}  // namespace figure_files
