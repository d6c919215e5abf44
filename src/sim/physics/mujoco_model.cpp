#include "sim/physics/mujoco_model.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

#include "sim/physics/rover_mjcf.hpp"
#include "sim/physics/terrain_mjcf.hpp"

namespace marsokhod::sim {
namespace {

struct VfsDeleter {
  void operator()(mjVFS* vfs) const {
    mj_deleteVFS(vfs);
    delete vfs;
  }
};

void copy_heightfield(mjModel& model, const Heightfield& field) {
  const int id = require_id(model, mjOBJ_HFIELD, kHeightfieldName);
  const std::size_t rows = static_cast<std::size_t>(model.hfield_nrow[id]);
  const std::size_t columns = static_cast<std::size_t>(model.hfield_ncol[id]);
  float* data = model.hfield_data + model.hfield_adr[id];
  // MuJoCo's row 0 lies at −y; an image's row 0 is its top, which a map puts at +y.
  for (std::size_t row = 0; row < rows; ++row) {
    for (std::size_t column = 0; column < columns; ++column) {
      data[row * columns + column] = static_cast<float>(field.image.at(rows - 1 - row, column));
    }
  }
}

// The soil's field at the ground's plane everywhere (terrain_mjcf.hpp): no rise. (On a heightfield
// the soil model copies its initial surface in when the rover's physics is built.)
void level_soil_field(mjModel& model, const TerrainSpec& terrain) {
  const int id = require_id(model, mjOBJ_HFIELD, kSoilFieldName);
  float* data = model.hfield_data + model.hfield_adr[id];
  const auto count = static_cast<std::size_t>(model.hfield_nrow[id]) *
                     static_cast<std::size_t>(model.hfield_ncol[id]);
  std::fill(data, data + count, soil_field_elevation(0.0, soil_field_above_m(terrain)));
}

}  // namespace

ModelPtr load_mjcf(const std::string& xml) {
  // mjVFS holds 2000 file names of 1000 bytes: too large for the stack.
  const std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const char* file_name = "marsokhod.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), file_name, static_cast<int>(xml.size())) != 0) {
    throw std::logic_error("physics: MuJoCo's virtual file system refused the model");
  }
  const int index = mj_findFileVFS(vfs.get(), file_name);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  std::array<char, 1000> error{};
  mjModel* model = mj_loadXML(file_name, vfs.get(), error.data(), static_cast<int>(error.size()));
  if (model == nullptr) {
    throw std::invalid_argument(std::string("physics: MuJoCo cannot build the model: ") +
                                error.data());
  }
  ModelPtr owned(model);
  // MuJoCo reports compiler warnings through the same buffer; the generated model has none.
  if (error[0] != '\0') {
    throw std::logic_error(std::string("physics: MuJoCo warns about the model: ") + error.data());
  }
  return owned;
}

ModelPtr load_rover_model(const Params& params, const TerrainSpec& terrain, double timestep_s) {
  ModelPtr model = load_mjcf(rover_mjcf(params, terrain, timestep_s));
  if (terrain.kind == TerrainKind::kHeightfield) copy_heightfield(*model, terrain.heightfield);
  if (terrain.ground.soil) level_soil_field(*model, terrain);
  return model;
}

int require_id(const mjModel& model, mjtObj type, const std::string& name) {
  const int id = mj_name2id(&model, type, name.c_str());
  if (id < 0) throw std::logic_error("physics: the generated model lacks " + name);
  return id;
}

}  // namespace marsokhod::sim
