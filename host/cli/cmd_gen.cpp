// evms gen --scene S --out DIR : a labelled scene on disk (one of the paper's scenes, or with
// --family TYPE a member of the scene family, host/gen/family.h).
#include <cstdio>
#include <filesystem>

#include "host/cli/common.h"
#include "host/cli/commands.h"
#include "host/gen/family.h"
#include "host/gen/scene_generator.h"
#include "host/write/event_writers.h"

namespace evms::cli {
namespace {

struct GenOptions {
  std::string scene = "rotation";
  std::string family;
  std::string out;
  gen::SceneConfig config;
  gen::FamilyPins pins;  // with --family: what the command line gave
};

void generate(GenOptions o) {
  if (!o.family.empty()) {
    const double duration = o.config.duration_s;
    o.config = gen::family_scene(o.family, o.config.seed, o.pins);
    if (duration > 0) o.config.duration_s = duration;
  } else if (!gen::parse_motion(o.scene, o.config.motion) ||
             !(o.config.motion == gen::Motion::kTranslation || o.config.motion == gen::Motion::kRotation ||
               o.config.motion == gen::Motion::kSixDof)) {
    throw std::invalid_argument("--scene: '" + o.scene + "' is not translation, rotation or 6dof (other motions: --family TYPE)");
  }
  if (o.config.duration_s <= 0) o.config.duration_s = 5.0;
  std::filesystem::create_directories(o.out);
  const SensorSize sensor{o.config.width, o.config.height};
  write::RpgEventsTxt events(o.out + "/events.txt", sensor);
  write::LabelledEventsCsv labels(o.out + "/labels.csv", sensor);
  write::TruthCsv truth(o.out + "/gt_tracks.csv");
  gen::SceneGenerator generator(o.config);
  Progress progress(true);
  std::vector<LabelledEvent> batch;
  std::vector<gen::TruthSample> samples;
  std::int64_t count = 0, noise = 0;
  while (generator.next(batch, samples)) {
    for (const LabelledEvent& e : batch) {
      events.write(e.event);
      labels.write(e);
      noise += e.label == kNoiseLabel;
    }
    for (const gen::TruthSample& s : samples) truth.write(s.t, s.object, s.x, s.y);
    count += static_cast<std::int64_t>(batch.size());
    batch.clear();
    samples.clear();
    progress.update(generator.progress(), count);
  }
  events.close();
  labels.close();
  truth.close();
  progress.done();
  std::printf("scene       %s%s, seed %llu\n", o.family.empty() ? "" : "family: ", gen::describe(o.config).c_str(),
              static_cast<unsigned long long>(o.config.seed));
  std::printf("objects     ");
  for (int i = 0; i < generator.object_count(); ++i) std::printf("%d=%s ", i, generator.object_name(i).c_str());
  std::printf("\nevents      %s (%s background noise)\n", grouped(count).c_str(), grouped(noise).c_str());
  std::printf("wrote       %s/events.txt, %s/labels.csv, %s/gt_tracks.csv\n", o.out.c_str(), o.out.c_str(), o.out.c_str());
}

}  // namespace

void register_gen(CLI::App& app) {
  auto o = std::make_shared<GenOptions>();
  o->config.duration_s = 0;  // unset: 5 s, or the family member's own
  CLI::App* cmd = app.add_subcommand("gen", "generate a labelled shapes scene: events.txt, labels.csv, gt_tracks.csv");
  cmd->add_option("--scene", o->scene, "one of the paper's scenes (the shapes poster): translation, rotation or 6dof")
      ->default_val(o->scene);
  cmd->add_option("--family", o->family, "instead, a member of the scene family drawn from --seed: still, translation, rotation, "
                  "zoom, 6dof, shake or crossing (seeds from 1000 are the validation split)");
  cmd->add_option("--speed", o->config.speed, "time scale of the motion (the paper's speed factor)")
      ->default_val(o->config.speed)->check(finite_in(gen::kSceneSpeedMin, gen::kSceneSpeedMax));
  cmd->add_option("--seed", o->config.seed, "random seed: the same seed gives the same bytes")->default_val(o->config.seed);
  cmd->add_option("--duration-s", o->config.duration_s, "length of the scene in seconds")
      ->default_str("5, or the family member's")->check(finite_in(gen::kSceneDurationMinS, gen::kSceneDurationMaxS));
  cmd->add_option("--noise-hz", o->config.noise_hz, "background activity per pixel, events/s (with --family: instead of the seed's draw)")
      ->default_val(o->config.noise_hz)->check(finite_in(0.0, gen::kSceneNoiseHzMax));
  cmd->add_option("--width", o->config.width, "sensor width, px (with --family: instead of the seed's draw)")->default_val(o->config.width)->check(CLI::Range(gen::kSceneSideMin, gen::kSceneSideMax));
  cmd->add_option("--height", o->config.height, "sensor height, px (with --family: instead of the seed's draw)")->default_val(o->config.height)->check(CLI::Range(gen::kSceneSideMin, gen::kSceneSideMax));
  cmd->add_option("--movers", o->config.movers, "shapes of the poster that move on their own")->default_val(0)->check(CLI::Range(0, 9));
  cmd->add_option("--objects", o->pins.objects, "with --family: this many shapes instead of the seed's draw")->check(CLI::Range(1, 16));
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->callback([o, cmd] {
    // With --family, the sensor and the noise are the seed's draw unless given.
    if (cmd->count("--width") || cmd->count("--height")) o->pins.width = o->config.width, o->pins.height = o->config.height;
    if (cmd->count("--noise-hz")) o->pins.noise_hz = o->config.noise_hz;
    generate(*o);
  });
}

}  // namespace evms::cli
