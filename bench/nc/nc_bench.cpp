// SPDX-License-Identifier: MIT
// Throughput of the NC front end in blocks per second: parse + interpret, from memory and from a
// file, and both passes (validation + execution) as `apcictl run` does them; Klartext LN lines.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "apci/nc/parser.h"
#include "apci/nc/program.h"

namespace apci::nc {
namespace {

constexpr std::size_t kBlocks = 200'000;

// Lines and arcs (I/J and R) round a square, with comments, like CAM output.
std::string make_program(std::size_t blocks) {
    std::string text = "%bench.nc\nN1 G17 G90 G25 F1000 (setup)\nN2 D1 G0 X0 Y0 Z0\n";
    char line[96];
    for (std::size_t i = 0; i < blocks; ++i) {
        const std::size_t n = i + 3;
        int len = 0;
        switch (i % 4) {
            case 0:
                len = std::snprintf(line, sizeof line, "N%zu G1 X10.125 Y0\n", n);
                break;
            case 1:
                len = std::snprintf(line, sizeof line, "N%zu G3 X20.125 Y10 I0 J10 ; arc\n", n);
                break;
            case 2:
                len = std::snprintf(line, sizeof line, "N%zu G2 X10.125 Y20 R10\n", n);
                break;
            default:
                len = std::snprintf(line, sizeof line, "N%zu G1 X0 Y0 Z-.5 (back)\n", n);
                break;
        }
        text.append(line, static_cast<std::size_t>(len));
    }
    text += "M30\n";
    return text;
}

// CAM-style Klartext: LN lines with N (and every other one with T under M128), 7 decimals.
std::string make_klartext_program(std::size_t blocks) {
    std::string text = "0  BEGIN PGM BENCH MM\n1  TOOL CALL 1 Z S8000\n2  L X+0 Y+0 Z+50 R0 FMAX\n";
    char line[192];
    for (std::size_t i = 0; i < blocks; ++i) {
        const std::size_t n = i + 3;
        const int len =
            i % 2 == 0
                ? std::snprintf(line, sizeof line,
                                "%zu LN X+36.0084 Y+6.177 Z-1.9209 NX-0.4658107 NY+0 NZ+0.8848844 "
                                "R0 F1000\n",
                                n)
                : std::snprintf(line, sizeof line,
                                "%zu LN X+36.0084 Y+6.177 Z-1.9209 NX-0.4658107 NY+0 NZ+0.8848844 "
                                "TX+0.0000000 TY+0.6558846 TZ+0.7548612 R0 M128\n",
                                n);
        text.append(line, static_cast<std::size_t>(len));
    }
    text += std::to_string(blocks + 3) + " END PGM BENCH MM\n";
    return text;
}

const std::string& program_text() {
    static const std::string text = make_program(kBlocks);
    return text;
}

const std::string& program_file() {
    static const std::string path = [] {
        std::string p = "/tmp/apci_nc_bench_" + std::to_string(::getpid()) + ".nc";
        std::FILE* f = std::fopen(p.c_str(), "wb");
        if (f == nullptr) std::abort();  // the benchmark cannot run without its program file
        std::fwrite(program_text().data(), 1, program_text().size(), f);
        std::fclose(f);
        return p;
    }();
    return path;
}

std::uint64_t drain(EventStream& s, benchmark::State& state) {
    Event ev;
    std::uint64_t n = 0;
    EventStream::Next r;
    while ((r = s.next(ev)) == EventStream::Next::kEvent) ++n;
    if (r == EventStream::Next::kError) state.SkipWithError(s.error().to_string().c_str());
    return n;
}

void set_rate(benchmark::State& state, std::uint64_t blocks_per_iteration) {
    state.counters["blocks/s"] = benchmark::Counter(
        static_cast<double>(blocks_per_iteration) * static_cast<double>(state.iterations()),
        benchmark::Counter::kIsRate);
}

void BM_ParseInterpretFromMemory(benchmark::State& state) {
    std::uint64_t blocks = 0;
    for ([[maybe_unused]] auto _ : state) {
        EventStream s = EventStream::from_text(program_text(), "bench.nc");
        benchmark::DoNotOptimize(drain(s, state));
        blocks = s.blocks_read();
    }
    set_rate(state, blocks);
}
BENCHMARK(BM_ParseInterpretFromMemory)->Unit(benchmark::kMillisecond);

void BM_ParseInterpretFromFile(benchmark::State& state) {
    std::uint64_t blocks = 0;
    for ([[maybe_unused]] auto _ : state) {
        Result<EventStream> s = EventStream::open_file(program_file());
        if (!s) {
            state.SkipWithError(s.error().to_string().c_str());
            break;
        }
        benchmark::DoNotOptimize(drain(s.value(), state));
        blocks = s.value().blocks_read();
    }
    set_rate(state, blocks);
}
BENCHMARK(BM_ParseInterpretFromFile)->Unit(benchmark::kMillisecond);

// Validation pass + execution pass; blocks/s counts each program block once.
void BM_ValidateThenExecuteFile(benchmark::State& state) {
    std::uint64_t blocks = 0;
    for ([[maybe_unused]] auto _ : state) {
        Result<Program> p = Program::load(program_file());
        if (!p) {
            state.SkipWithError(p.error().to_string().c_str());
            break;
        }
        Result<EventStream> s = p.value().events();
        if (!s) {
            state.SkipWithError(s.error().to_string().c_str());
            break;
        }
        benchmark::DoNotOptimize(drain(s.value(), state));
        blocks = p.value().summary().blocks;
    }
    set_rate(state, blocks);
}
BENCHMARK(BM_ValidateThenExecuteFile)->Unit(benchmark::kMillisecond);

void BM_KlartextLnFromMemory(benchmark::State& state) {
    static const std::string text = make_klartext_program(kBlocks);
    std::uint64_t blocks = 0;
    for ([[maybe_unused]] auto _ : state) {
        EventStream s = EventStream::from_text(text, "bench.h");
        benchmark::DoNotOptimize(drain(s, state));
        blocks = s.blocks_read();
    }
    set_rate(state, blocks);
}
BENCHMARK(BM_KlartextLnFromMemory)->Unit(benchmark::kMillisecond);

void BM_ParseOneLine(benchmark::State& state) {
    ParsedLine out;
    Diagnostic err;
    const std::string_view line = "N12345 G3 X20.125 Y10 I0 J10 ; arc";
    for ([[maybe_unused]] auto _ : state) {
        benchmark::DoNotOptimize(parse_din_line(line, 1, "bench.nc", out, err));
        benchmark::DoNotOptimize(out.block.axis[0].value);
    }
    state.counters["blocks/s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ParseOneLine);

}  // namespace
}  // namespace apci::nc

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    std::remove(apci::nc::program_file().c_str());
    return 0;
}
