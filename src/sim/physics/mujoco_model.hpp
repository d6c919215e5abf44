// Owning handles for MuJoCo's model and data, and the loading of the generated rover model from
// memory (MuJoCo's virtual file system: no temporary file).
#pragma once

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

#include "core/params.hpp"
#include "sim/physics/terrain.hpp"

namespace marsokhod::sim {

struct ModelDeleter {
  void operator()(mjModel* model) const { mj_deleteModel(model); }
};
struct DataDeleter {
  void operator()(mjData* data) const { mj_deleteData(data); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// Compiles MJCF text. Throws std::invalid_argument with MuJoCo's message on failure.
ModelPtr load_mjcf(const std::string& xml);

// rover_mjcf() compiled, with the heightfield's elevations copied in (image top row at +y).
ModelPtr load_rover_model(const Params& params, const TerrainSpec& terrain, double timestep_s);

// The id of a named object; throws std::logic_error if the generated model lacks it.
int require_id(const mjModel& model, mjtObj type, const std::string& name);

}  // namespace marsokhod::sim
