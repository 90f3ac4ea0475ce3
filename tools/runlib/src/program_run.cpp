// SPDX-License-Identifier: MIT
#include "apci/run/program_run.h"

#include <utility>

#include "dry_run.h"

namespace apci::run {

nc::Result<RunInputs> load_run_inputs(const RunInputFiles& files) {
    RunInputs in;
    in.tools_name = files.tools_name;
    in.corrections_name = files.corrections_name;
    if (files.tools) {
        auto loaded = files.tools_is_text ? nc::parse_tool_table(*files.tools, "<tools>")
                                          : nc::load_tool_table(*files.tools);
        if (!loaded) return loaded.error();
        in.tools = std::move(loaded.value());
        in.tools_given = true;
    }
    if (files.corrections) {
        auto loaded = nc::load_correction_table(*files.corrections);
        if (!loaded) return loaded.error();
        in.corrections = std::move(loaded.value());
        in.corrections_given = true;
    }
    if (files.plc) {
        auto loaded = load_plc_script(*files.plc);
        if (!loaded) return loaded.error();
        in.plc = std::move(loaded.value());
    }
    return in;
}

nc::Diagnostic name_missing_input(nc::Diagnostic d, const RunInputs& inputs) {
    if (!inputs.tools_given && d.undefined == nc::Undefined::kTool)
        d.message += " (no " + inputs.tools_name + " given)";
    if (!inputs.corrections_given && d.undefined == nc::Undefined::kCorrectionRow)
        d.message += " (no " + inputs.corrections_name + " given)";
    return d;
}

std::optional<SelfApproachMode> self_approach_mode(std::string_view name) noexcept {
    if (name == "warn") return SelfApproachMode::kWarn;
    if (name == "error") return SelfApproachMode::kError;
    if (name == "off") return SelfApproachMode::kOff;
    return std::nullopt;
}

bool embedded_emulator(std::string_view uri) noexcept {
    return uri.empty() || uri.starts_with("emu:");
}

ProgramRun::ProgramRun(apci::Board& board, RunSink& sink, const RunInputs& inputs,
                       const RunSettings& settings)
    : board_(board),
      inputs_(inputs),
      head_(chain(sink, settings)),
      executor_(board, head_, &inputs.tools, inputs.plc ? &*inputs.plc : nullptr,
                &inputs.corrections) {
    executor_.set_avoid_bottlenecks(settings.bottleneck_blocks);
    // With the check on a thread of its own (warn, threads: chain() made the check's pipeline
    // and the writers' behind it), the reader follows the check's ring: beside the executor
    // while the check falls behind, beside the check while it keeps up.
    const RingFill* check_ring = check_ && pipeline_ && output_ ? &*pipeline_ : nullptr;
    executor_.set_read_ahead(settings.threads, settings.cpus, helpers_beside_check(settings),
                             check_ring);
    executor_.set_lost_link_hint(settings.lost_link_hint);
    options_ = executor_.interpreter_options();
    bottleneck_blocks_ = settings.bottleneck_blocks;
    threads_ = settings.threads;
    dry_run_ = settings.dry_run_first && settings.self_approach == SelfApproachMode::kError;
}

ProgramRun::~ProgramRun() {
    pipeline_.reset();  // its thread calls the check: ended and joined first
    check_.reset();     // it calls the writers' pipeline
    output_.reset();
}

HelperCpu ProgramRun::helpers_beside_check(const RunSettings& settings) noexcept {
    return settings.threads && settings.self_approach == SelfApproachMode::kWarn
               ? HelperCpu::kEither
               : HelperCpu::kOther;
}

RunSink& ProgramRun::chain(RunSink& sink, const RunSettings& settings) {
    const SelfApproachMode mode = settings.self_approach;
    if (!settings.threads) {
        if (mode == SelfApproachMode::kOff) return sink;
        return check_.emplace(sink, mode);
    }
    switch (mode) {
        case SelfApproachMode::kOff:
            return pipeline_.emplace(sink, settings.cpus);
        case SelfApproachMode::kWarn:
            // The check on a thread of its own, on the CPU the executor leaves (it is the
            // run's longest chain of work on a program of many contours), fed through the
            // pipeline; the writers behind it on another, fed through a second, which runs
            // wherever there is time (beside the executor, or beside the check where the
            // executor is the longer): docs/performance.md, "Three helper threads". The
            // writers' pipeline measures the segments, on the lighter thread. The check, asleep
            // on its empty ring (at the start), is woken for the first batch: on a program of
            // many contours it is the longer chain, and every batch it waits for there is
            // waited for again at the end (docs/performance.md, "The run's ends").
            return pipeline_.emplace(
                check_.emplace(output_.emplace(sink, settings.cpus, helpers_beside_check(settings)),
                               mode),
                settings.cpus, HelperCpu::kOther, 1);
        case SelfApproachMode::kError:  // on the executor's thread, where it stops the run
            break;
    }
    return check_.emplace(pipeline_.emplace(sink, settings.cpus), mode);
}

std::optional<nc::Diagnostic> ProgramRun::open_validated(const ProgramSource& source) {
    source_ = source;
    single_.reset();
    stream_.reset();
    program_.reset();
    auto loaded = source.text ? nc::Program::from_text(*source.text, source.name, options_)
                              : nc::Program::load(source.path, options_);
    if (!loaded) return name_missing_input(loaded.error(), inputs_);
    program_.emplace(std::move(loaded).value());
    auto events = program_->events();
    if (!events) return events.error();
    stream_.emplace(std::move(events).value());
    if (dry_run_) {
        RunSettings dry;
        dry.bottleneck_blocks = bottleneck_blocks_;
        dry.threads = threads_;
        return detail::self_approach_dry_run(board_, inputs_, source, dry);
    }
    return std::nullopt;
}

std::optional<nc::Diagnostic> ProgramRun::open_one_pass(const ProgramSource& source) {
    source_ = source;
    single_.reset();
    stream_.reset();
    program_.reset();
    if (source.text) {
        single_.emplace(nc::SinglePass::from_text(*source.text, source.name, options_));
        return std::nullopt;
    }
    auto opened = nc::SinglePass::open_file(source.path, options_);
    if (!opened) return name_missing_input(opened.error(), inputs_);
    single_.emplace(std::move(opened).value());
    return std::nullopt;
}

std::optional<nc::Diagnostic> ProgramRun::validate_first() {
    if (!single_) return std::nullopt;
    return open_validated(ProgramSource(source_));
}

std::uint64_t ProgramRun::program_bytes() const noexcept {
    return single_ ? single_->size() : 0;
}

std::uint64_t ProgramRun::validated_blocks() const noexcept {
    return program_ ? program_->summary().blocks : 0;
}

nc::EventStream& ProgramRun::events() {
    return single_ ? single_->events() : *stream_;
}

RunOutcome ProgramRun::run() {
    RunOutcome out = executor_.run(events());
    if (pipeline_) pipeline_->finish();  // every event through the check
    if (output_) output_->finish();      // and to the caller's sink
    if (check_) check_->results(out);
    return out;
}

std::optional<nc::Diagnostic> ProgramRun::finish(RunOutcome& outcome) {
    std::uint64_t blocks = validated_blocks();
    if (single_) {
        auto valid = single_->finish();
        if (!valid) return name_missing_input(valid.error(), inputs_);
        blocks = valid.value().blocks;
    }
    outcome.totals.file = source_.name;
    outcome.totals.blocks = blocks;
    return std::nullopt;
}

nc::Result<RunOutcome> run_program(apci::Board& board, RunSink& sink, const RunInputs& inputs,
                                   const ProgramSource& source, const RunSettings& settings) {
    ProgramRun program(board, sink, inputs, settings);
    if (auto refused = program.open_validated(source)) return std::move(*refused);
    RunOutcome outcome = program.run();
    if (auto refused = program.finish(outcome)) return std::move(*refused);
    return outcome;
}

}  // namespace apci::run
