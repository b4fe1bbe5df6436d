// `filmback submit`'s tasks as data (core/cmd/slurm_job.h).
#include "core/cmd/slurm_job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/util/error.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

TEST(SlurmJob, TheJobFolderSitsNextToTheFirstOutput) {
  EXPECT_EQ(default_job_dir("renders/shot.####.exr"), fs::path("renders/shot.filmback-job"));
  EXPECT_EQ(default_job_dir("out.exr"), fs::path("out.filmback-job"));
  EXPECT_EQ(default_job_dir("####.exr"), fs::path("render.filmback-job"));
}

TEST(SlurmJob, NamesSaySceneFrameAndTile) {
  EXPECT_EQ(task_name("shot", 12, 3, 8), "fb:shot:f0012:t3/8");
  EXPECT_EQ(task_name("shot", std::nullopt, 3, 8), "fb:shot:t3/8");
  EXPECT_EQ(task_name("shot", -2, std::nullopt, 8), "fb:shot:f-0002");
}

TEST(SlurmJob, ArraysStayWithinMaxArraySizeAndCoverEveryTask) {
  const std::vector<ArrayChunk> chunks = array_chunks(2500, 1001);
  ASSERT_EQ(chunks.size(), 3u);
  uint64_t next = 0;
  for (const ArrayChunk& c : chunks) {
    EXPECT_EQ(c.offset, next);
    EXPECT_LE(c.count, 1001u);
    next += c.count;
  }
  EXPECT_EQ(next, 2500u);
  EXPECT_TRUE(array_chunks(0, 1001).empty());
}

SubmitCommand frames_command() {
  SubmitCommand c;
  c.scene = "/scenes/shot.gltf";
  c.outputs = {"/renders/shot.####.exr", "/renders/shot.####.png"};
  c.tiles = 4;
  c.frames = "3-7:2";
  c.checkpoint_every = "30s";
  c.render_args = {"--spp", "16"};
  return c;
}

// The value after `option` in `args`, or "" when absent.
std::string value_of(const std::vector<std::string>& args, const std::string& option) {
  const auto at = std::find(args.begin(), args.end(), option);
  return at == args.end() || at + 1 == args.end() ? "" : *(at + 1);
}

TEST(SlurmJob, TaskIndexIsFrameIndexTimesTilesPlusTile) {
  const SlurmJob job = plan_slurm_job(frames_command(), true, 5);
  ASSERT_EQ(job.tile_tasks.size(), 12u);
  ASSERT_EQ(job.merge_tasks.size(), 3u);
  EXPECT_EQ(job.dir, fs::path("/renders/shot.filmback-job"));
  std::set<fs::path> parts;
  for (size_t i = 0; i < job.tile_tasks.size(); ++i) {
    const TileTask& t = job.tile_tasks[i];
    const int64_t frame = 3 + 2 * int64_t(i / 4);
    EXPECT_EQ(t.frame, frame);
    EXPECT_EQ(t.tile, i % 4);
    EXPECT_EQ(t.render_args.front(), "/scenes/shot.gltf");
    EXPECT_EQ(value_of(t.render_args, "--spp"), "16");
    EXPECT_EQ(value_of(t.render_args, "--frame"), std::to_string(frame));
    EXPECT_EQ(value_of(t.render_args, "--tile"), std::to_string(i % 4) + "/4");
    EXPECT_EQ(value_of(t.render_args, "--tile-plan"), (job.dir / "plan.json").string());
    EXPECT_EQ(value_of(t.render_args, "-o"), t.part.string());
    EXPECT_EQ(value_of(t.render_args, "--checkpoint"), t.checkpoint.string());
    EXPECT_EQ(value_of(t.render_args, "--checkpoint-every"), "30s");
    EXPECT_EQ(t.part.parent_path(), job.dir / "parts");
    parts.insert(t.part);
    const MergeTask& m = job.merge_tasks[i / 4];
    EXPECT_EQ(m.parts[i % 4], t.part);
  }
  EXPECT_EQ(parts.size(), 12u);  // every part its own file
  EXPECT_EQ(job.merge_tasks[1].outputs,
            (std::vector<fs::path>{"/renders/shot.0005.exr", "/renders/shot.0005.png"}));
  ASSERT_EQ(job.tile_arrays.size(), 3u);  // 12 tasks in arrays of at most 5
  EXPECT_EQ(job.tile_arrays[2].offset + job.tile_arrays[2].count, 12u);
  EXPECT_TRUE(job.threads_from_slurm);
}

TEST(SlurmJob, WithoutFramesNoFrameIsPassedAndOutputsStayAsTyped) {
  SubmitCommand c = frames_command();
  c.frames.clear();
  c.outputs = {"/renders/still.exr"};
  c.checkpoint_every.clear();
  c.render_args = {"--threads", "4"};
  const SlurmJob job = plan_slurm_job(c, false, 1001);
  ASSERT_EQ(job.tile_tasks.size(), 4u);
  for (const TileTask& t : job.tile_tasks) {
    EXPECT_EQ(value_of(t.render_args, "--frame"), "");
    EXPECT_EQ(value_of(t.render_args, "--tile-plan"), "");
    EXPECT_EQ(value_of(t.render_args, "--checkpoint"), "");
    EXPECT_TRUE(t.checkpoint.empty());
  }
  EXPECT_EQ(job.merge_tasks.at(0).outputs, std::vector<fs::path>{"/renders/still.exr"});
  EXPECT_FALSE(job.threads_from_slurm);
}

TEST(SlurmJob, RefusesWhatSubmitSetsForEveryTask) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"-o", "x.exr"},
                                             {"-ox.exr"},
                                             {"--output=x.exr"},
                                             {"--tile=1/2"},
                                             {"--crop", "0,0,8,8"},
                                             {"--resume"},
                                             {"--frame", "3"},
                                             {"--checkpoint-every", "5m"}}) {
    SubmitCommand c = frames_command();
    c.render_args = args;
    EXPECT_THROW(plan_slurm_job(c, false, 1001), UsageError) << args.front();
  }
  SubmitCommand no_pattern = frames_command();
  no_pattern.outputs = {"/renders/shot.exr"};
  EXPECT_THROW(plan_slurm_job(no_pattern, false, 1001), UsageError);
  SubmitCommand too_many = frames_command();
  too_many.frames = "1-50000";
  too_many.tiles = 8;
  EXPECT_THROW(plan_slurm_job(too_many, false, 1001), UsageError);
}

}  // namespace
}  // namespace fb
