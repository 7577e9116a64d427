#include "cli_options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

#include "drape/core/input_error.h"
#include "drape/sim/extremes_grid.h"

namespace drape::app {
namespace {

bool parseSize(const std::string& text, int& w, int& h) {
  const auto x = text.find('x');
  if (x == std::string::npos) return false;
  auto [p1, e1] = std::from_chars(text.data(), text.data() + x, w);
  auto [p2, e2] = std::from_chars(text.data() + x + 1, text.data() + text.size(), h);
  return e1 == std::errc() && e2 == std::errc() && p1 == text.data() + x && p2 == text.data() + text.size() &&
         w >= 16 && h >= 16 && w <= 8192 && h <= 8192;
}

// A whole number from 1 to max, or an InputError naming the option.
int count(const std::string& s, const std::string& option, const char* what, int max) {
  int n = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), n);
  if (error != std::errc() || end != s.data() + s.size() || n < 1 || n > max)
    throw InputError(option + ": '" + s + "' is not a number of " + what + " from 1 to " + std::to_string(max));
  return n;
}

// A value written into an sbatch script's #SBATCH line: letters, digits and -_:.,+ only.
std::string sbatchValue(const std::string& s, const std::string& option) {
  const bool ok = !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_:.,+", c) != nullptr;
  });
  if (!ok) throw InputError(option + ": '" + s + "' is not a Slurm name or time (letters, digits, -_:.,+)");
  return s;
}

void requireOneOf(const std::string& option, const std::string& value, std::initializer_list<const char*> valid) {
  std::string list;
  for (const char* v : valid) {
    if (value == v) return;
    list += (list.empty() ? "" : "|") + std::string(v);
  }
  throw InputError(option + ": '" + value + "' is not one of " + list);
}

}  // namespace

std::string usageText() {
  return R"(Usage:
  drape [SCENE.json]                      open the desktop application (default scene if none given)
  drape --info FILE [scene options]       describe a pattern, scene or avatar file
  drape --simulate SCENE -o OUT.(obj|glb|ply|stl) [--solver none|preview|drape|full] [--stats STATS.json] [--max-sim-time S]
                                          [--from STATE.obj] [--png OUT.png [--view V] [--size WxH] [--mode M]]
                                          build the garment, run the solver, write the garment (and a picture)
  drape --render SCENE -o OUT.png [--view front|back|left|right|three-quarter|all] [--size WxH]
                                          [--mode shaded|wireframe|strain|domains|contacts] [--simulate none|preview|drape|full]
                                          [--from STATE.obj]
                                          render a PNG headless (no display server needed)
  drape --render BODY.(obj|glb|gltf|fbx|ply|stl) -o OUT.png [--avatar-units U] [--view V] [--size WxH]
                                          render a body mesh on its own (mannequin previews)
  drape --bench SCENE [--solver preview|drape|full] [--sweep KEY=V1,V2,...]... [--levels] [--reference REF.json]
        [--rounds N] [-o REPORT.json] [--plot TRADE.png] [--max-sim-time S]
                                          speed/accuracy trade: each sweep value (and level) against a tight reference
                                          drape, kept in REF.json and reused when it exists (docs/TRADE.md)
  drape --trade-plot REPORT.json... -o TRADE.png
                                          the Pareto plot of trade reports, one series per scene
  drape --scaling-plot SCALING.json -o SCALING.png
                                          time to rest and peak memory against the vertex count, log-log (a
                                          report of bench/scaling.py)
  drape --write-pattern PATTERN -o OUT.(json|dxf|pdf|svg)
                                          the pattern (GarmentCode JSON, DXF-AAMA, or a scene's) as GarmentCode
                                          JSON, as DXF-AAMA, or at full scale with a 10 cm check square (PDF, SVG)
  drape --trade-levels REPORT.json... -o LEVELS.json
                                          the GUI's speed/accuracy levels: the candidates on the reports' Pareto front
  drape --bench SCENE --extremes [--solver preview|drape|full] [--cell NAME]... [-o REPORT.json] [--max-sim-time S]
                                          every physics setting at both ends of its range (and the hard
                                          combinations) in each stage: finite, diverged only when said why,
                                          nothing inside the body (exit 1 when a cell fails); --cell runs only
                                          the cells named (e.g. "stretch max")
  drape --make-avatar MEASUREMENTS.(yaml|json) -o AVATAR.(obj|glb)
                                          a smooth watertight mannequin from body measurements (cm)
  drape --batch MANIFEST.json -o OUTDIR [--jobs N] [--list]
                                          every job of a batch manifest (docs/FORMATS.md), N at a time (default:
                                          the core count, the cores shared among them), each in OUTDIR/<id>/; then
                                          OUTDIR/summary.csv, summary.json and contact_sheet.png. Jobs with a
                                          done.json are skipped, so the same command finishes a killed batch.
                                          --list prints the job ids only. Progress: [done/failed/total].
                                          Exit 5 when some jobs failed
  drape --batch MANIFEST.json -o OUTDIR --slurm [--partition P] [--time T] [--cpus-per-task N] [--tasks N]
                                          submit the unfinished jobs to Slurm as one job array (one task per job
                                          by default) and a job that gathers the summary when it ends; OUTDIR must
                                          be on a filesystem the nodes share. Again: resubmits what did not finish
  drape --batch MANIFEST.json -o OUTDIR --shard I/N
                                          only the jobs whose index is I modulo N, no summary (an array task)
  drape --batch MANIFEST.json -o OUTDIR --gather
                                          the summary and contact sheet of what has run, running nothing
  drape --list-settings                   every setting with its default, unit and meaning
  drape --list-fabrics                    the fabric presets
  drape --help | --version

Scene options (every headless mode):
  SCENE may be a scene file or a bare pattern file (GarmentCode JSON, or DXF-AAMA: pieces without seams).
  --avatar FILE            avatar or collider mesh (obj, glb, gltf, fbx, ply, stl)
  --avatar-units U        unit of the avatar file: m, cm, mm or in (inches); default m
  --fabric PRESET          fabric of every panel (see --list-fabrics)
  --set KEY=VALUE          override any setting by its dotted name (repeatable; see --list-settings)
  --threads N              use at most N threads (default: every core)

Solvers (--solver for --simulate and --bench, --simulate for --render; default: the scene's solver.stage):
  none     the placed garment
  preview  the fast preview (the drape's model by L-BFGS) until it is at rest
  drape    the Backward-Euler Newton drape from the placed garment until at rest or solver.max_sim_time
  full     the preview, then the Newton drape from the preview state
  --from STATE.obj starts the stage at the vertex positions of an OBJ that drape wrote for the same scene (none: that
  state as it is; preview, full: the preview from it at rest; drape: the drape from it as from a preview's hand-over)
Exit status: 0 on success, 1 on bad input or failure (one line on stderr names the file and the problem), 3 when the
  solver diverged (the last good state is written), 4 when a simulated result fails its quality verdict (settings
  quality.*: stretch, body penetration, self-intersections, at rest; one "warning: quality:" line per failed check).
)";
}

CliOptions parseCommandLine(int argc, char** argv) {
  CliOptions o;
  bool modeSet = false;
  auto setMode = [&](Mode m, const std::string& flag) {
    if (modeSet) throw InputError(flag + ": only one of --info, --simulate, --render, --help, --version at a time");
    o.mode = m;
    modeSet = true;
  };
  auto value = [&](int& i, const std::string& flag) -> std::string {
    if (i + 1 >= argc) throw InputError(flag + ": missing value");
    return argv[++i];
  };
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      setMode(Mode::Help, a);
    } else if (a == "--version") {
      setMode(Mode::Version, a);
    } else if (a == "--list-settings") {
      setMode(Mode::ListSettings, a);
    } else if (a == "--list-fabrics") {
      setMode(Mode::ListFabrics, a);
    } else if (a == "--info") {
      setMode(Mode::Info, a);
      o.scene.input = value(i, a);
    } else if (a == "--make-avatar") {
      setMode(Mode::MakeAvatar, a);
      o.scene.input = value(i, a);
    } else if (a == "--bench") {
      setMode(Mode::Bench, a);
      o.scene.input = value(i, a);
    } else if (a == "--batch") {
      setMode(Mode::Batch, a);
      o.batch = value(i, a);
    } else if (a == "--jobs") {
      o.jobs = count(value(i, a), a, "jobs", 1024);
    } else if (a == "--list") {
      o.list = true;
    } else if (a == "--shard") {
      const std::string s = value(i, a);
      const auto slash = s.find('/');
      const char* const first = s.data();
      const auto [mid, e1] =
          std::from_chars(first, first + (slash == std::string::npos ? s.size() : slash), o.shardIndex);
      bool ok = slash != std::string::npos && e1 == std::errc() && mid == first + slash;
      if (ok) {
        const auto [end, e2] = std::from_chars(first + slash + 1, first + s.size(), o.shardCount);
        ok = e2 == std::errc() && end == first + s.size();
      }
      if (!ok || o.shardCount < 1 || o.shardCount > kMaxArrayTasks || o.shardIndex < 0 || o.shardIndex >= o.shardCount)
        throw InputError(a + ": '" + s + "' is not I/N with 0 <= I < N <= " + std::to_string(kMaxArrayTasks));
    } else if (a == "--gather") {
      o.gather = true;
    } else if (a == "--slurm") {
      o.slurm = true;
    } else if (a == "--partition") {
      o.partition = sbatchValue(value(i, a), a);
    } else if (a == "--time") {
      o.timeLimit = sbatchValue(value(i, a), a);
    } else if (a == "--cpus-per-task") {
      o.cpusPerTask = count(value(i, a), a, "CPUs", 1024);
    } else if (a == "--tasks") {
      o.tasks = count(value(i, a), a, "array tasks", kMaxArrayTasks);
    } else if (a == "--threads") {
      o.threads = count(value(i, a), a, "threads", 1024);
    } else if (a == "--sweep") {
      o.sweeps.push_back(value(i, a));
    } else if (a == "--extremes") {
      o.extremes = true;
    } else if (a == "--cell") {
      o.cells.push_back(value(i, a));
    } else if (a == "--levels") {
      o.levels = true;
    } else if (a == "--reference") {
      o.reference = value(i, a);
    } else if (a == "--plot") {
      o.plot = value(i, a);
    } else if (a == "--rounds") {
      o.rounds = count(value(i, a), a, "rounds", 100);
    } else if (a == "--trade-plot") {
      setMode(Mode::TradePlot, a);
    } else if (a == "--trade-levels") {
      setMode(Mode::TradeLevels, a);
    } else if (a == "--scaling-plot") {
      setMode(Mode::ScalingPlot, a);
    } else if (a == "--write-pattern") {
      setMode(Mode::WritePattern, a);
      o.scene.input = value(i, a);
    } else if (a == "--render") {
      setMode(Mode::Render, a);
      o.scene.input = value(i, a);
    } else if (a == "--simulate") {
      // In --render mode --simulate names the stage to run first; otherwise it is the mode.
      if (o.mode == Mode::Render) {
        o.simulateStage = value(i, a);
        requireOneOf(a, o.simulateStage, {"none", "preview", "drape", "full"});
      } else {
        setMode(Mode::Simulate, a);
        o.scene.input = value(i, a);
      }
    } else if (a == "-o" || a == "--output") {
      o.output = value(i, a);
    } else if (a == "--png") {
      o.png = value(i, a);
    } else if (a == "--stats") {
      o.stats = value(i, a);
    } else if (a == "--solver") {
      o.solver = value(i, a);
      requireOneOf(a, o.solver, {"none", "preview", "drape", "full"});
    } else if (a == "--view") {
      o.view = value(i, a);
      o.viewGiven = true;
      requireOneOf(a, o.view, {"front", "back", "left", "right", "three-quarter", "all"});
    } else if (a == "--mode") {
      o.renderMode = value(i, a);
      requireOneOf(a, o.renderMode, {"shaded", "wireframe", "strain", "domains", "contacts"});
    } else if (a == "--size") {
      const std::string s = value(i, a);
      if (!parseSize(s, o.width, o.height)) throw InputError(a + ": '" + s + "' is not WxH with 16..8192 pixels each");
    } else if (a == "--max-sim-time") {
      const std::string s = value(i, a);
      try {
        o.maxSimTime = std::stod(s);
      } catch (...) {
        o.maxSimTime = -1;
      }
      if (!(o.maxSimTime > 0) || !std::isfinite(o.maxSimTime))
        throw InputError(a + ": '" + s + "' is not a positive number of seconds");
    } else if (a == "--from") {
      o.from = value(i, a);
    } else if (a == "--avatar") {
      o.scene.avatarFile = value(i, a);
    } else if (a == "--avatar-units") {
      o.scene.avatarUnits = value(i, a);
      requireOneOf(a, o.scene.avatarUnits, {"m", "cm", "mm", "in"});
    } else if (a == "--fabric") {
      o.scene.fabricPreset = value(i, a);
    } else if (a == "--set") {
      const std::string kv = value(i, a);
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0) throw InputError("--set: '" + kv + "' is not KEY=VALUE");
      o.scene.overrides.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    } else if (!a.empty() && a[0] == '-') {
      throw InputError("unknown option '" + a + "' (see drape --help)");
    } else {
      positional.push_back(a);
    }
  }
  if (o.mode == Mode::Gui) {
    if (positional.size() > 1) throw InputError("more than one scene given: '" + positional[1] + "'");
    if (!positional.empty()) o.scene.input = positional[0];
  } else if (o.mode == Mode::TradePlot || o.mode == Mode::TradeLevels) {
    const std::string flag = o.mode == Mode::TradePlot ? "--trade-plot" : "--trade-levels";
    if (positional.empty()) throw InputError(flag + ": no trade report given (REPORT.json from drape --bench -o)");
    if (o.output.empty()) throw InputError(flag + ": missing -o OUTPUT");
    o.reports = positional;
  } else if (o.mode == Mode::ScalingPlot) {
    if (positional.size() != 1)
      throw InputError("--scaling-plot: give one scaling report (SCALING.json from bench/scaling.py)");
    if (o.output.empty()) throw InputError("--scaling-plot: missing -o OUTPUT");
    o.reports = positional;
  } else if (!positional.empty()) {
    throw InputError("unexpected argument '" + positional[0] + "' (see drape --help)");
  }
  if ((o.mode == Mode::Simulate || o.mode == Mode::Render || o.mode == Mode::MakeAvatar ||
       o.mode == Mode::WritePattern) &&
      o.output.empty())
    throw InputError(std::string(o.mode == Mode::Render         ? "--render"
                                 : o.mode == Mode::Simulate     ? "--simulate"
                                 : o.mode == Mode::WritePattern ? "--write-pattern"
                                                                : "--make-avatar") +
                     ": missing -o OUTPUT");
  if (o.mode == Mode::Batch && o.output.empty() && !o.list) throw InputError("--batch: missing -o OUTDIR");
  if ((o.jobs > 0 || o.list || o.shardCount > 0 || o.gather || o.slurm) && o.mode != Mode::Batch)
    throw InputError("--jobs, --list, --shard, --gather, --slurm: only with --batch");
  if ((!o.partition.empty() || !o.timeLimit.empty() || o.cpusPerTask > 0 || o.tasks > 0) && !o.slurm)
    throw InputError("--partition, --time, --cpus-per-task, --tasks: only with --slurm");
  if (int(o.list) + int(o.gather) + int(o.slurm) + int(o.shardCount > 0) > 1)
    throw InputError("--list, --gather, --slurm, --shard: one at a time");
  if (o.extremes && (o.mode != Mode::Bench || !o.sweeps.empty() || o.levels))
    throw InputError("--extremes: only with --bench, and not with --sweep or --levels");
  if ((o.levels || !o.reference.empty() || !o.plot.empty() || !o.sweeps.empty() || o.rounds != 1) &&
      o.mode != Mode::Bench)
    throw InputError("--sweep, --levels, --reference, --plot, --rounds: only with --bench");
  if (o.extremes && (!o.reference.empty() || !o.plot.empty() || o.rounds != 1))
    throw InputError("--reference, --plot, --rounds: not with --extremes");
  if (!o.cells.empty() && !o.extremes) throw InputError("--cell: only with --bench --extremes");
  for (const std::string& name : o.cells) {
    const auto all = extremeCells();
    if (std::none_of(all.begin(), all.end(), [&](const ExtremeCell& c) { return c.name == name; }))
      throw InputError("--cell: no extremes cell '" + name + "' (the cells are the first column of --extremes)");
  }
  if (!o.from.empty() && o.mode != Mode::Simulate && o.mode != Mode::Render)
    throw InputError("--from: only with --simulate or --render");
  return o;
}

}  // namespace drape::app
