// The viewer's loop: input -> camera -> one frame of the budget -> display -> title and chart.
#include "view/viewer.h"

#include <GLFW/glfw3.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "accel/factory.h"
#include "image/io.h"
#include "render/resource_limits.h"
#include "scene/camera_spline.h"
#include "scene/load.h"
#include "view/display_image.h"
#include "view/fly_camera.h"
#include "view/frame_chart.h"
#include "view/gl_window.h"
#include "view/path_recorder.h"
#include "view/progressive_view.h"
#include "view/view_status.h"

namespace tuneray {

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Keys pressed since the last frame, in order (toggles act once per press, not per frame held).
struct KeyQueue {
  std::vector<int> pressed;
};

void on_key(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  static_cast<KeyQueue*>(glfwGetWindowUserPointer(window))->pressed.push_back(key);
}

constexpr const char* kHelp =
    "keys: W/A/S/D fly, E/Q up/down, Shift faster, drag with the left button to look;\n"
    "      G strip chart, M adaptive sampling, B sampler, N denoiser, P save .png, X save .exr,\n"
    "      H this help, Esc quit";

// The formats image/io.h writes (it reads more).
bool writable_image(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".exr" || ext == ".pfm";
}

void check_options(const ViewerOptions& o) {
  if (o.width < 1 || o.height < 1) throw std::invalid_argument("view: --size must be positive");
  if (!(o.frame_ms > 0)) throw std::invalid_argument("view: --frame-ms must be positive");
  if (o.frames < 0) throw std::invalid_argument("view: --frames must not be negative");
  if (o.path_frames < 1) throw std::invalid_argument("view: --path-frames must be at least 1");
  if (!o.screenshot.empty() && o.frames == 0)
    throw std::invalid_argument("view: --screenshot needs --frames N (the frame to capture)");
  // Checked before the window opens, so a typo does not cost the whole run.
  if (!o.screenshot.empty() && !writable_image(o.screenshot))
    throw std::invalid_argument("view: --screenshot '" + o.screenshot +
                                "': expected a .png, .exr or .pfm file");
}

// The cameras of path `index` at `count` evenly spaced positions; scenes without paths fly the
// automatic one as path 0 (as `tune` does).
std::vector<CameraDesc> path_cameras(const Scene& scene, int index, int count) {
  const int paths = static_cast<int>(scene.camera_paths.size());
  if (paths == 0 && index == 0) return sample_camera_path(automatic_camera_path(scene), count);
  if (index < 0 || index >= paths)
    throw std::invalid_argument("view: bad --path " + std::to_string(index) + ": the scene has " +
                                std::to_string(paths) + " camera path(s)");
  return sample_camera_path(scene.camera_paths[index], count);
}

const char* sampler_name(SamplerKind kind) {
  return kind == SamplerKind::kBlueNoise ? "bluenoise" : "pcg";
}

// Running totals for the summary line of a scripted run.
struct FrameTotals {
  int frames = 0;
  double wall_ms = 0, render_ms = 0, spp = 0, longest_ms = 0;
  void add(double wall, double render, double frame_spp) {
    ++frames;
    longest_ms = std::max(longest_ms, wall);
    wall_ms += wall;
    render_ms += render;
    spp += frame_spp;
  }
};

// What the keys toggle besides the view's own settings.
struct ViewerControls {
  bool show_chart = false;
  int saved = 0;  // images saved so far (their file name's number)
};

// Acts on one key press; false for quit.
bool apply_key(int key, const ViewerOptions& o, ProgressiveView& view, ViewerControls& controls) {
  QualityOptions q = view.settings().quality;
  switch (key) {
    case GLFW_KEY_ESCAPE:
      return false;
    case GLFW_KEY_G:
      controls.show_chart = !controls.show_chart;
      break;
    case GLFW_KEY_M:
      q.adaptive = !q.adaptive;
      view.set_quality(q);
      break;
    case GLFW_KEY_B:
      q.sampler =
          q.sampler == SamplerKind::kBlueNoise ? SamplerKind::kPcg : SamplerKind::kBlueNoise;
      view.set_quality(q);
      break;
    case GLFW_KEY_N:
      q.denoise = !q.denoise;
      view.set_quality(q);
      std::cout << "view: denoiser " << (q.denoise ? "on" : "off") << std::endl;
      break;
    case GLFW_KEY_P:
    case GLFW_KEY_X: {
      const std::string path = o.save_prefix + "-" + std::to_string(controls.saved++) +
                               (key == GLFW_KEY_P ? ".png" : ".exr");
      WriteOptions write_options;
      write_options.exposure = o.exposure;
      // A failed save (a full disk, a folder that does not exist) must not end the session.
      try {
        write_image(path, view.image(), write_options);
        std::cout << "saved     " << path << std::endl;
      } catch (const std::exception& e) {
        std::cout << "view: cannot save " << path << ": " << e.what() << std::endl;
      }
      break;
    }
    case GLFW_KEY_H:
      std::cout << kHelp << std::endl;
      break;
    default:
      break;
  }
  return true;
}

// The cursor between frames: it turns the view only while the left button stays held.
struct MouseDrag {
  double x = 0, y = 0;
  bool held = false;
};

FlyInput read_fly_input(GLFWwindow* window, MouseDrag& drag) {
  FlyInput input;
  auto held = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
  input.move.z = static_cast<float>(held(GLFW_KEY_W) - held(GLFW_KEY_S));
  input.move.x = static_cast<float>(held(GLFW_KEY_D) - held(GLFW_KEY_A));
  input.move.y = static_cast<float>(held(GLFW_KEY_E) - held(GLFW_KEY_Q));
  if (held(GLFW_KEY_LEFT_SHIFT) || held(GLFW_KEY_RIGHT_SHIFT)) input.move *= 4.0f;
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  const bool button = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  if (button && drag.held) {
    input.turn_right_px = static_cast<float>(x - drag.x);
    input.turn_up_px = static_cast<float>(drag.y - y);  // screen y grows downwards
  }
  drag = {x, y, button};
  return input;
}

FrameKind frame_kind(const std::string& tuner_mode) {
  if (tuner_mode == "search") return FrameKind::kSearch;
  if (tuner_mode == "exploit") return FrameKind::kExploit;
  return FrameKind::kYardstick;
}

}  // namespace

bool viewer_available() {
  return true;
}

int run_viewer(const ViewerOptions& o) {
  check_options(o);
  check_render_memory(o.width, o.height);
  // The window first: without a display the command fails at once, not after a scene load.
  GlWindow window(o.width, o.height, "tuneray view " + o.scene);
  KeyQueue keys;
  glfwSetWindowUserPointer(window.handle(), &keys);
  glfwSetKeyCallback(window.handle(), on_key);

  std::unique_ptr<tbb::global_control> thread_limit;
  if (const int threads = clamp_threads(o.threads); threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));

  LoadOptions load_options;
  load_options.scenes_dir = o.scenes_dir;
  const Scene scene = load_scene(o.scene, load_options);
  if (o.camera < 0 || o.camera >= static_cast<int>(scene.cameras.size()))
    throw std::invalid_argument("view: bad --camera " + std::to_string(o.camera) + ": scene '" +
                                o.scene + "' has cameras 0.." +
                                std::to_string(scene.cameras.size() - 1));
  std::vector<CameraDesc> playback;
  if (o.path >= 0) playback = path_cameras(scene, o.path, o.path_frames);

  std::unique_ptr<Accel> accel = make_accel(o.accel, o.bvh);
  GeometryView geometry{scene.positions.data(), scene.positions.size(), scene.triangles.data(),
                        scene.triangles.size()};
  accel->build(geometry);

  RenderSettings settings;
  settings.width = o.width;
  settings.height = o.height;
  settings.max_bounces = o.max_bounces;
  settings.seed = o.seed;
  settings.quality = o.quality;
  const CameraDesc start = playback.empty() ? scene.cameras[o.camera] : playback.front();
  std::optional<ViewTuner> tuner;
  if (o.tune) {
    tuner.emplace(scene, settings, o.tuning);
    tuner->set_camera(start);
  }
  ProgressiveView view(scene, *accel, settings, start, o.frame_ms);
  const BBox bounds = scene.bounds();
  FlyCamera fly(start, default_fly_speed(bounds.lo, bounds.hi));
  PathRecorder recorder("recorded");
  recorder.add(start);
  FrameChart chart(240);
  ViewerControls controls;
  controls.show_chart = o.chart;
  bool playing = !playback.empty();
  if (!o.quiet && o.frames == 0) std::cout << kHelp << std::endl;

  ViewStatus status;
  status.scene = o.scene;
  status.accel = o.tune ? std::string("tuned online")
                        : std::string(accel->name()) + (o.bvh.empty() ? "" : " " + o.bvh);
  FrameTotals totals;
  double smoothed_ms = 0;
  MouseDrag drag;
  Clock::time_point frame_start = Clock::now(), last_title = frame_start;
  double last_frame_ms = o.frame_ms;

  for (int frame = 0; o.frames == 0 || frame < o.frames; ++frame) {
    window.poll_events();
    if (window.should_close()) break;
    bool quit = false;
    for (int key : keys.pressed) quit = !apply_key(key, o, view, controls) || quit;
    keys.pressed.clear();
    if (quit) break;
    const FlyInput input = read_fly_input(window.handle(), drag);

    bool moved = false;
    if (playing && frame > 0) {
      const size_t index = std::min(static_cast<size_t>(frame), playback.size() - 1);
      if (!(playback[index].position == view.camera().position &&
            playback[index].target == view.camera().target)) {
        fly.set_desc(playback[index]);
        view.set_camera(playback[index]);
        moved = true;
      }
      if (index + 1 == playback.size()) playing = false;
    }
    const float seconds = static_cast<float>(std::min(last_frame_ms, 100.0) / 1000.0);
    if (fly.apply(input, seconds)) {
      playing = false;
      view.set_camera(fly.desc());
      moved = true;
    }
    if (moved) {
      recorder.add(view.camera());
      if (tuner) tuner->set_camera(view.camera());
    }

    if (tuner) view.set_accel(tuner->next_accel());
    const FrameResult result = view.render_frame();
    if (tuner) tuner->report(result);
    window.draw_image(view.display_bytes(o.exposure), o.width, o.height);
    if (controls.show_chart)
      window.draw_chart(chart.points(o.frame_ms), chart.budget_y(o.frame_ms));
    if (!o.screenshot.empty() && frame + 1 == o.frames) {
      int width = 0, height = 0;
      std::vector<uint8_t> shown = window.read_pixels(width, height);
      write_display_image(o.screenshot, shown, width, height);
    }
    window.present();

    const Clock::time_point now = Clock::now();
    last_frame_ms = ms_between(frame_start, now);
    frame_start = now;
    chart.add(last_frame_ms, tuner ? frame_kind(tuner->status().mode) : FrameKind::kPlain);
    smoothed_ms = smoothed_ms > 0 ? 0.9 * smoothed_ms + 0.1 * last_frame_ms : last_frame_ms;
    // The first frame carries one-time costs (threads, caches): not in the summary.
    if (frame > 0) totals.add(last_frame_ms, result.ms, result.spp);
    if (ms_between(last_title, now) > 250 || frame + 1 == o.frames) {
      status.frame_ms = smoothed_ms;
      status.render_ms = result.ms;
      status.frame_spp = result.spp;
      status.film_spp = view.film_spp();
      status.adaptive = view.settings().quality.adaptive;
      status.sampler = sampler_name(view.settings().quality.sampler);
      status.playing_path = playing;
      if (tuner) status.tuning = format_tuning(tuner->status());
      window.set_title(format_title(status));
      last_title = now;
    }
  }

  if (!o.record.empty()) recorder.write(o.record);
  if (!o.quiet) {
    if (totals.frames > 0) {
      const double mean_ms = totals.wall_ms / totals.frames;
      std::printf(
          "view      %d frames after the first: %.2f ms per frame (%.1f fps), longest %.2f ms, "
          "render %.2f ms, %.2f spp per frame; film %.1f spp\n",
          totals.frames, mean_ms, 1000.0 / mean_ms, totals.longest_ms,
          totals.render_ms / totals.frames, totals.spp / totals.frames, view.film_spp());
    }
    if (tuner)
      std::printf("tuning    %s into %s (key %s), %d failed builds\n",
                  format_tuning(tuner->status()).c_str(), o.tuning.db_path.c_str(),
                  tuner->tuning_key().c_str(), tuner->failed_builds());
    if (!o.screenshot.empty()) std::printf("wrote     %s\n", o.screenshot.c_str());
    if (!o.record.empty())
      std::printf("wrote     %s (%zu keyframes)\n", o.record.c_str(),
                  recorder.path().keyframes.size());
  }
  return 0;
}

}  // namespace tuneray
