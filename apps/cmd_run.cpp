// `rtsph run SCENE`: headless batch run with progress, exports, checkpoints, an instability
// guard and a summary. Exit codes: 0 done, 1 I/O or other error, 2 bad input (scene, arguments,
// checkpoint), 3 unstable, 128+signal after SIGINT (130) / SIGTERM (143).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <limits>

#include "apps/commands.h"
#include "apps/progress.h"
#include "apps/run_checkpoint.h"
#include "apps/run_signals.h"
#include "apps/run_summary.h"
#include "io/atomic_file.h"
#include "io/checkpoint.h"
#include "io/exporter.h"
#include "scene/params.h"
#include "scene/scene.h"
#include "solvers/health.h"
#include "solvers/simulation.h"
#include "apps/sim_backend.h"

namespace rtsph::app {

namespace {
struct RunOptions {
  std::string scene;
  double until = -1;
  long long steps = -1;
  int threads = 0;
  std::string backend;  // empty: the scene's solver.backend, else cpu
  std::vector<std::string> sets;
  std::string export_dir, format = "csv", attributes = "all", stats_json;
  double every = 0.02;
  // Surface formats (vdb, obj, ply-mesh); io::check_surface_options validates them.
  double voxel_size = std::numeric_limits<double>::quiet_NaN(), surface_radius = 1, adaptivity = 0;  // NaN: default
  bool quiet = false;
  // Checkpoints.
  double checkpoint_every = 0;  // simulated seconds; 0 = only at the end / on interruption
  std::string checkpoint_dir, resume;
  // Instability guard.
  double max_density_error = kDefaultMaxDensityError;
  bool recover = false;
  int max_retries = 3;
  long long snapshot_every = 100;
};

/// The largest k ≥ 0 with k·every ≤ t (1e-12 s tolerance). Frames and checkpoints are due when
/// this grows, so the schedule depends on the simulated time only and a resumed run continues
/// it exactly where the original run was.
long long slot_of(double t, double every) {
  const double tt = t + 1e-12;
  long long k = std::max(0LL, static_cast<long long>(std::floor(tt / every)));
  while (double(k + 1) * every <= tt) ++k;
  while (k > 0 && double(k) * every > tt) --k;
  return k;
}

const char* signal_name(int sig) { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal"; }

/// Halves the time step (fixed dt, or CFL number and max_dt) and describes the change.
std::string halve_time_step(SimSpec& s) {
  if (s.time_step_mode == TimeStepMode::Fixed) {
    const double old = s.dt;
    s.dt *= 0.5;
    return fmt::format("solver.time_step.dt {:.4g} -> {:.4g} s", old, s.dt);
  }
  const double cfl = s.cfl, max_dt = s.max_dt;
  s.cfl *= 0.5;
  s.max_dt *= 0.5;
  return fmt::format("solver.time_step.cfl {:.4g} -> {:.4g}, max_dt {:.4g} -> {:.4g} s", cfl, s.cfl, max_dt, s.max_dt);
}

/// --set on a resumed run may change the live parameters except gravity (c0 was derived from it
/// when the run started, and a checkpoint does not store derived parameters), and end_time, which
/// only sets the default --until. The stored scene fixes the rest.
bool resume_allows(const SimSpec& stored, const SimSpec& wanted) {
  SimSpec allowed = stored;
  copy_live_parameters(wanted, allowed);
  allowed.gravity = stored.gravity;
  allowed.end_time = wanted.end_time;
  return scene_to_json(allowed) == scene_to_json(wanted);
}

/// Refuses, naming the first --set that changes what the checkpoint fixes.
void check_resume_overrides(const SimSpec& stored, const SimSpec& wanted, const std::vector<std::string>& sets) {
  if (resume_allows(stored, wanted)) return;
  std::string bad;
  for (const auto& set : sets) {
    SimSpec one = stored;
    apply_override(one, set);
    if (!resume_allows(stored, one)) {
      bad = fmt::format("--set {}: {} is fixed by the checkpoint's scene; ", set, set.substr(0, set.find('=')));
      break;
    }
  }
  std::vector<std::string> keys;
  for (const auto& p : parameter_table())
    if (p.live && p.key != "gravity") keys.push_back(p.key);
  throw std::invalid_argument(fmt::format("{}--set with --resume can only change {} and end_time", bad,
                                          fmt::join(keys, ", ")));
}

int run(const RunOptions& o) {
  if (o.scene.empty() && o.resume.empty()) {
    throw std::invalid_argument("run: a SCENE is required (or --resume CHECKPOINT)");
  }
  SimSpec spec;
  BackendSimulation sim;
  fs::path resumed_from;
  if (!o.resume.empty()) {
    resumed_from = resolve_resume_path(o.resume);
    inspect_checkpoint(resumed_from);  // a damaged file is refused before any scene work
    if (!o.scene.empty()) {
      spec = load_scene(o.scene);
      for (const auto& s : o.sets) apply_override(spec, s);
      sim = BackendSimulation::make(spec, o.threads, choose_backend(o.backend, spec, "cpu"));
      try {
        io::read_checkpoint(resumed_from, *sim, scene_hash(spec));
      } catch (const io::CheckpointError& e) {
        const std::string what = e.what();
        if (what.find("scene hash mismatch") == std::string::npos) throw;
        throw io::CheckpointError(what + "; omit SCENE and --set to resume with the scene stored next to the checkpoint");
      }
    } else {
      const SimSpec stored = load_checkpoint_scene(resumed_from);
      spec = stored;
      for (const auto& s : o.sets) apply_override(spec, s);
      check_resume_overrides(stored, spec, o.sets);
      sim = BackendSimulation::make(stored, o.threads, choose_backend(o.backend, spec, "cpu"));
      io::read_checkpoint(resumed_from, *sim, scene_hash(stored));
      if (scene_to_json(spec) != scene_to_json(stored)) sim->set_live_parameters(spec);
    }
  } else {
    spec = load_scene(o.scene);
    for (const auto& s : o.sets) apply_override(spec, s);
    sim = BackendSimulation::make(spec, o.threads, choose_backend(o.backend, spec, "cpu"));
  }
  const bool resumed = !resumed_from.empty();
  if (resumed && o.until >= 0 && o.until < sim->time())
    throw std::invalid_argument(fmt::format("--until {} s is before the checkpoint's time, {:.6g} s: nothing to run",
                                            o.until, sim->time()));
  const double until = o.until >= 0 ? o.until : (o.steps >= 0 ? std::numeric_limits<double>::infinity() : spec.end_time);
  const std::uint64_t max_steps = o.steps >= 0 ? std::uint64_t(o.steps) : std::numeric_limits<std::uint64_t>::max();
  const std::string stem = safe_file_stem(spec.name);

  // Where checkpoints go: --checkpoint-dir, else EXPORT/checkpoints or ./checkpoints when
  // --checkpoint-every asks for them. Without either, only an interrupted or failed run writes
  // one, next to the exported frames or in the current directory.
  fs::path ckpt_dir = o.checkpoint_dir;
  if (ckpt_dir.empty() && o.checkpoint_every > 0) {
    ckpt_dir = o.export_dir.empty() ? fs::path("checkpoints") : fs::path(o.export_dir) / "checkpoints";
  }
  const fs::path fallback_base = o.export_dir.empty() ? fs::path(".") : fs::path(o.export_dir);
  if (!ckpt_dir.empty()) io::ensure_directory(ckpt_dir);
  // Where the summary goes must exist before the run, not be found missing after it.
  if (!o.stats_json.empty()) io::check_file_target(o.stats_json);

  std::unique_ptr<io::Exporter> exporter;
  long long frame_slot = slot_of(sim->time(), o.every);  // frames up to this slot are written
  if (!o.export_dir.empty()) {
    io::ExportOptions eo = io::parse_attributes(o.attributes);
    eo.resume = resumed;
    eo.surface.spacing_m = spec.spacing;
    eo.surface.dimension = spec.dimension;
    if (!std::isnan(o.voxel_size) && !(o.voxel_size > 0)) {
      throw std::invalid_argument(fmt::format("--voxel-size {}: must be a positive length in m", o.voxel_size));
    }
    eo.surface.voxel_size_m = std::isnan(o.voxel_size) ? 0 : o.voxel_size;
    eo.surface.radius_factor = o.surface_radius;
    eo.surface.adaptivity = o.adaptivity;
    eo.surface.threads = o.threads;
    exporter = io::make_exporter(o.format, o.export_dir, eo);
    if (!resumed) exporter->write_frame(int(frame_slot), sim->time(), sim->fluid());
  }
  long long ckpt_slot = o.checkpoint_every > 0 ? slot_of(sim->time(), o.checkpoint_every) : 0;

  const auto s0 = sim->stats();
  if (!o.quiet) {
    std::fprintf(stderr, "rtsph run: %s (%dD, %s, %s), %zu fluid + %zu boundary particles, c0 = %.1f m/s\n",
                 spec.name.c_str(), spec.dimension, spec.method.c_str(), sim.description().c_str(),
                 s0.fluid_particles, s0.boundary_particles, s0.c0);
    if (resumed) {
      std::fprintf(stderr, "rtsph run: resumed from %s at t = %.6g s (step %llu)\n", resumed_from.c_str(),
                   sim->time(), static_cast<unsigned long long>(sim->step_count()));
    }
  }

  // State kept for the guard and for the final checkpoint.
  StateSnapshot good;
  good.capture(*sim);
  long long since_snapshot = 0;
  SimSpec live = sim->spec();
  int retries = 0;
  std::string status = "completed", last_checkpoint;
  double unstable_at = -1;  // the time the run failed at, when it did
  std::uint64_t last_checkpoint_step = std::numeric_limits<std::uint64_t>::max();
  int rc = 0;

  // Saves the current state to `file`; false (with the error printed) if that failed.
  auto save_at = [&](const fs::path& file) -> bool {
    try {
      save_checkpoint(file, *sim);
      last_checkpoint = file.string();
      last_checkpoint_step = sim->step_count();
      return true;
    } catch (const io::IoError& e) {
      std::fprintf(stderr, "rtsph: %s\n", e.what());
      return false;
    }
  };
  // After a failed write in `failed_dir` (disk full, read-only): saves the state to $TMPDIR
  // or the current directory, so a run never loses its state to an I/O error.
  auto rescue = [&](const fs::path& failed_dir) {
    std::string errors;
    const fs::path file = save_checkpoint_somewhere(*sim, fallback_dirs(failed_dir),
                                                    fmt::format("rtsph_rescue_{}.ckpt", stem), errors);
    if (file.empty()) {
      std::fprintf(stderr, "rtsph: could not save the simulation state anywhere: %s\n", errors.c_str());
      return;
    }
    last_checkpoint = file.string();
    last_checkpoint_step = sim->step_count();
    std::fprintf(stderr, "rtsph: the simulation state (t = %.6g s, step %llu) was saved to %s instead\n", sim->time(),
                 static_cast<unsigned long long>(sim->step_count()), file.c_str());
  };
  auto save = [&](const fs::path& file) {
    if (save_at(file)) return true;
    rescue(file.parent_path().empty() ? fs::path(".") : file.parent_path());
    return false;
  };
  auto resume_hint = [&] {
    if (!last_checkpoint.empty()) std::fprintf(stderr, "rtsph: continue with: rtsph run --resume %s\n", last_checkpoint.c_str());
  };
  auto checkpoint_path = [&](const char* reason) {
    return ckpt_dir.empty() ? fallback_base / fmt::format("rtsph_{}_{}.ckpt", reason, stem)
                            : ckpt_dir / checkpoint_file_name(sim->step_count());
  };

  install_stop_handlers();
  const double progress_total = std::isfinite(until) ? until : double(max_steps);
  Progress progress("run", progress_total, o.quiet);
  const auto t0 = std::chrono::steady_clock::now();
  const std::uint64_t start_step = sim->step_count();
  long long steps = 0;
  while (!stop_signal() && sim->time() < until && sim->step_count() - start_step < max_steps) {
    sim->step();
    ++steps;

    if (auto issue = check_health(*sim, o.max_density_error)) {
      progress.finish();
      std::fprintf(stderr, "rtsph: %s\n", issue->message.c_str());
      if (o.recover && retries < o.max_retries) {
        ++retries;
        good.restore(*sim);
        const std::string change = halve_time_step(live);
        sim->set_live_parameters(live);
        frame_slot = slot_of(sim->time(), o.every);
        if (o.checkpoint_every > 0) ckpt_slot = slot_of(sim->time(), o.checkpoint_every);
        since_snapshot = 0;
        std::fprintf(stderr, "rtsph: retry %d/%d from the last good state (t = %.6g s, step %llu) with %s\n", retries,
                     o.max_retries, sim->time(), static_cast<unsigned long long>(sim->step_count()), change.c_str());
        continue;
      }
      if (o.recover) std::fprintf(stderr, "rtsph: giving up after %d retries (--max-retries)\n", retries);
      unstable_at = sim->time();
      good.restore(*sim);
      status = "unstable";
      rc = 3;
      save(checkpoint_path("unstable"));
      if (!last_checkpoint.empty() && last_checkpoint_step == sim->step_count()) {
        std::fprintf(stderr, "rtsph: the last good state (t = %.6g s, step %llu) is saved in %s\n", sim->time(),
                     static_cast<unsigned long long>(sim->step_count()), last_checkpoint.c_str());
      }
      break;
    }
    if (++since_snapshot >= o.snapshot_every) {
      good.capture(*sim);
      since_snapshot = 0;
    }

    try {
      if (exporter) {
        const long long slot = slot_of(sim->time(), o.every);
        if (slot > frame_slot) {
          exporter->write_frame(int(slot), sim->time(), sim->fluid());
          frame_slot = slot;
        }
      }
    } catch (const io::IoError& e) {
      progress.finish();
      std::fprintf(stderr, "rtsph: export failed: %s\n", e.what());
      status = "io-error";
      rc = 1;
      if (ckpt_dir.empty() || !save_at(ckpt_dir / checkpoint_file_name(sim->step_count()))) rescue(o.export_dir);
      resume_hint();
      break;
    }
    if (o.checkpoint_every > 0) {
      const long long slot = slot_of(sim->time(), o.checkpoint_every);
      if (slot > ckpt_slot) {
        ckpt_slot = slot;
        if (!save(ckpt_dir / checkpoint_file_name(sim->step_count()))) {
          progress.finish();
          status = "io-error";
          rc = 1;
          resume_hint();
          break;
        }
        good.capture(*sim);
        since_snapshot = 0;
      }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    progress.update(std::isfinite(until) ? sim->time() : double(sim->step_count() - start_step),
                    fmt::format("{:.0f} steps/s", wall > 0 ? steps / wall : 0.0));
  }
  progress.finish();
  const int sig = stop_signal();
  restore_default_stop_handlers();

  if (rc == 0 && sig != 0) {
    status = "interrupted";
    rc = 128 + sig;
    if (last_checkpoint_step != sim->step_count()) save(checkpoint_path("interrupted"));
    std::fprintf(stderr, "rtsph: stopped by %s at t = %.6g s (step %llu)%s%s\n", signal_name(sig), sim->time(),
                 static_cast<unsigned long long>(sim->step_count()), last_checkpoint.empty() ? "" : "; checkpoint: ",
                 last_checkpoint.c_str());
    resume_hint();
  } else if (rc == 0 && !ckpt_dir.empty() && last_checkpoint_step != sim->step_count()) {
    if (!save(ckpt_dir / checkpoint_file_name(sim->step_count()))) {
      status = "io-error";
      rc = 1;
      resume_hint();
    }
  }

  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  RunSummary summary = make_summary(*sim, steps, wall, o.threads);
  summary.status = status;
  summary.unstable_at_s = unstable_at;
  summary.retries = retries;
  summary.checkpoint = last_checkpoint;
  if (!o.quiet || o.stats_json.empty()) print_summary(summary, stdout);
  if (!o.stats_json.empty()) {
    const std::string text = summary_json(summary);
    try {
      io::write_file_atomic(o.stats_json, [&](std::ostream& os) { os << text << "\n"; });
    } catch (const io::IoError& e) {
      // The directory went away or the disk filled during the run: the summary still reaches
      // the user (with --quiet it went only to that file).
      std::fprintf(stderr, "rtsph: %s\n", e.what());
      if (o.quiet) std::fprintf(stdout, "%s\n", text.c_str());
      return rc == 0 ? 1 : rc;
    }
  }
  return rc;
}
}  // namespace

void add_run_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RunOptions>();
  auto* cmd = app.add_subcommand("run", "Run a scene headless and print a summary");
  cmd->add_option("scene", o->scene, "Scene file or built-in name (see `rtsph scenes`); optional with --resume");
  cmd->add_option("--until", o->until, "Stop at this simulated time (s); default: the scene's end_time")
      ->check(non_negative_number());
  cmd->add_option("--steps", o->steps, "Stop after this many steps")->check(non_negative_number());
  cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
  cmd->add_option("--backend", o->backend, "Where the solver runs: cpu, gpu (OpenGL compute, headless through EGL) "
                                           "or auto (= cpu for run); default: the scene's solver.backend")
      ->check(CLI::IsMember({"cpu", "gpu", "auto"}));
  cmd->add_option("--set", o->sets, "Override a scene parameter, e.g. --set fluid.spacing=0.01");
  CLI::Option* exp = cmd->add_option("--export", o->export_dir, "Write frames into this directory");
  // The options below shape the frames --export writes; without it they would do nothing, so
  // they are refused rather than silently ignored.
  cmd->add_option("--every", o->every, "Simulated seconds between exported frames")
      ->check(positive_number())->capture_default_str()->needs(exp);
  cmd->add_option("--format", o->format,
                  "Export format: particles (csv, vtk, ply) or the fluid surface (vdb: level set; obj, "
                  "ply-mesh: triangle mesh; 3D scenes only)")->capture_default_str()->needs(exp);
  cmd->add_option("--voxel-size", o->voxel_size, "Surface formats: level-set voxel edge in m (default: 0.4 x spacing)")
      ->needs(exp);
  cmd->add_option("--surface-radius", o->surface_radius,
                  "Surface formats: particle sphere radius as a multiple of the spacing (default 1)")->needs(exp);
  cmd->add_option("--adaptivity", o->adaptivity,
                  "obj, ply-mesh: mesh adaptivity from 0 (uniform, default) to 1 (fewest triangles)")->needs(exp);
  cmd->add_option("--attributes", o->attributes, "Exported arrays: all or a list of position,velocity,density,pressure,id")
      ->capture_default_str()->needs(exp);
  cmd->add_option("--stats-json", o->stats_json, "Write the summary as JSON to this file");
  cmd->add_flag("--quiet", o->quiet, "No progress output; with --stats-json the summary goes only to that file");
  cmd->add_option("--checkpoint-every", o->checkpoint_every,
                  "Write a checkpoint every S simulated seconds, and at the end")
      ->check(non_negative_number());
  cmd->add_option("--checkpoint-dir", o->checkpoint_dir,
                  "Directory for checkpoints (default: EXPORT/checkpoints or ./checkpoints)");
  cmd->add_option("--resume", o->resume,
                  "Continue from this checkpoint (or the newest ckpt_*.ckpt in this directory)");
  cmd->add_option("--max-density-error", o->max_density_error,
                  "Stop as unstable when (rho-rho0)/rho0 exceeds this (default 0.5)")
      ->check(positive_number());
  cmd->add_flag("--recover", o->recover, "When unstable, halve dt and retry from the last good state");
  cmd->add_option("--max-retries", o->max_retries, "Retries allowed by --recover (default 3)")->check(CLI::Range(0, 30));
  cmd->add_option("--snapshot-every", o->snapshot_every,
                  "Steps between in-memory copies of the last good state (default 100)")
      ->check(CLI::Range(1LL, std::numeric_limits<long long>::max()));
  cmd->callback([o, &exit_code] { exit_code = guarded([&] { return run(*o); }); });
}

}  // namespace rtsph::app
