// AtmosphereModel: the tables, their disk cache, and CPU queries through the shared code.
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "model_cache.hpp"
#include "model_tables.hpp"

namespace thalassa::atmosphere {
namespace {

// Bump when the tables' meaning changes (model.glsl's parameterisations, sample counts or
// precomputation order), so that old cache files are not read.
constexpr int kModelVersion = 1;
constexpr char kMagic[8] = {'T', 'H', 'A', 'L', 'A', 'T', 'M', '1'};

std::string table_layout() {
  std::ostringstream out;
  out << "version=" << kModelVersion << ";T=" << glsl::TRANSMITTANCE_TEXTURE_WIDTH << 'x'
      << glsl::TRANSMITTANCE_TEXTURE_HEIGHT << ";S=" << glsl::SCATTERING_TEXTURE_NU_SIZE << 'x'
      << glsl::SCATTERING_TEXTURE_MU_S_SIZE << 'x' << glsl::SCATTERING_TEXTURE_MU_SIZE << 'x'
      << glsl::SCATTERING_TEXTURE_R_SIZE << ";E=" << glsl::IRRADIANCE_TEXTURE_WIDTH << 'x'
      << glsl::IRRADIANCE_TEXTURE_HEIGHT << ";samples=" << glsl::TRANSMITTANCE_SAMPLE_COUNT << ','
      << glsl::SINGLE_SCATTERING_SAMPLE_COUNT << ',' << glsl::MULTIPLE_SCATTERING_SAMPLE_COUNT
      << ',' << glsl::SCATTERING_DENSITY_SAMPLE_COUNT << ','
      << glsl::INDIRECT_IRRADIANCE_SAMPLE_COUNT << ';';
  return out.str();
}

// 64-bit FNV-1a, for the cache file's name (the full key is stored in the file and compared).
std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string default_cache_dir() {
  if (const char* dir = std::getenv("THALASSA_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return std::string(xdg) + "/thalassa";
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return std::string(home) + "/.cache/thalassa";
  }
  return {};
}

template <typename Table>
void write_table(std::ofstream& out, const Table& table) {
  const std::vector<float>& data = table.data();
  const std::uint64_t count = data.size();
  out.write(reinterpret_cast<const char*>(&count), sizeof count);
  out.write(reinterpret_cast<const char*>(data.data()),
            static_cast<std::streamsize>(count * sizeof(float)));
}

template <typename Table>
bool read_table(std::ifstream& in, Table& table) {
  std::uint64_t count = 0;
  in.read(reinterpret_cast<char*>(&count), sizeof count);
  if (!in || count != table.data().size()) return false;
  in.read(reinterpret_cast<char*>(table.data().data()),
          static_cast<std::streamsize>(count * sizeof(float)));
  if (!in) return false;
  for (float v : table.data()) {
    if (!std::isfinite(v) || v < 0.0f) return false;
  }
  return true;
}

}  // namespace

std::string cache_key(const AtmosphereParameters& parameters) {
  return parameters.key() + table_layout();
}

std::string cache_file_name(const std::string& key) {
  char name[64];
  std::snprintf(name, sizeof name, "atmosphere-%016llx.bin",
                static_cast<unsigned long long>(fnv1a(key)));
  return name;
}

bool load_cache(const std::string& path, const std::string& key, ModelTables& tables) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  char magic[8];
  in.read(magic, sizeof magic);
  if (!in || !std::equal(magic, magic + 8, kMagic)) return false;
  std::uint64_t key_size = 0;
  in.read(reinterpret_cast<char*>(&key_size), sizeof key_size);
  if (!in || key_size != key.size()) return false;
  std::string stored(key_size, '\0');
  in.read(stored.data(), static_cast<std::streamsize>(key_size));
  if (!in || stored != key) return false;
  tables.transmittance =
      glsl::Texture2D(glsl::TRANSMITTANCE_TEXTURE_WIDTH, glsl::TRANSMITTANCE_TEXTURE_HEIGHT);
  tables.scattering =
      glsl::Texture3D(glsl::SCATTERING_TEXTURE_WIDTH, glsl::SCATTERING_TEXTURE_HEIGHT,
                      glsl::SCATTERING_TEXTURE_DEPTH);
  tables.single_mie_scattering = tables.scattering;
  tables.irradiance =
      glsl::Texture2D(glsl::IRRADIANCE_TEXTURE_WIDTH, glsl::IRRADIANCE_TEXTURE_HEIGHT);
  return read_table(in, tables.transmittance) && read_table(in, tables.scattering) &&
         read_table(in, tables.single_mie_scattering) && read_table(in, tables.irradiance) &&
         in.peek() == std::char_traits<char>::eof();
}

// Writes to a unique temporary name in the cache folder, then renames: concurrent processes
// (parallel tests) never see a half-written file. Returns an empty string or why it failed.
std::string store_cache(const std::string& path, const std::string& key,
                        const ModelTables& tables) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  if (ec) return "cannot create " + fs::path(path).parent_path().string() + ": " + ec.message();
  const std::string temporary =
      path + ".tmp" + std::to_string(::getpid()) + "-" +
      std::to_string(std::hash<std::thread::id>()(std::this_thread::get_id()));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return "cannot write " + temporary;
    out.write(kMagic, sizeof kMagic);
    const std::uint64_t key_size = key.size();
    out.write(reinterpret_cast<const char*>(&key_size), sizeof key_size);
    out.write(key.data(), static_cast<std::streamsize>(key.size()));
    write_table(out, tables.transmittance);
    write_table(out, tables.scattering);
    write_table(out, tables.single_mie_scattering);
    write_table(out, tables.irradiance);
    out.close();
    if (!out) {
      fs::remove(temporary, ec);
      return "cannot write " + temporary;
    }
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    fs::remove(temporary, ec);
    return "cannot rename to " + path;
  }
  return {};
}

namespace {

glsl::vec3 dv(const glm::dvec3& v) { return glsl::vec3(v.x, v.y, v.z); }

}  // namespace

struct AtmosphereModel::State {
  AtmosphereParameters parameters;
  glsl::AtmosphereParameters atmosphere;
  // Immutable once built; shared by the models of the same parameters alive in the process.
  std::shared_ptr<const ModelTables> tables;
  double precompute_seconds = 0.0;
  double load_seconds = 0.0;
  std::string cache_status;
  std::string cache_path;
};

AtmosphereModel::AtmosphereModel() : state_(std::make_unique<State>()) {}
AtmosphereModel::~AtmosphereModel() = default;

namespace {

// The tables of the models alive in this process, by cache key: a program that creates a
// renderer per frame (thalassa fly) reads the cache file once, not per frame (about 40 ms each).
// Weak, so that the tables go when the last model using them does.
struct LiveTables {
  std::mutex mutex;
  std::map<std::string, std::weak_ptr<const ModelTables>> by_key;
};

LiveTables& live_tables() {
  static LiveTables live;
  return live;
}

}  // namespace

std::shared_ptr<const AtmosphereModel> AtmosphereModel::create(
    const AtmosphereParameters& parameters, const PrecomputeOptions& options) {
  parameters.validate();
  std::shared_ptr<AtmosphereModel> model(new AtmosphereModel());
  State& s = *model->state_;
  s.parameters = parameters;
  s.atmosphere = to_glsl(parameters);

  const std::string key = cache_key(parameters);
  const std::string dir = options.cache_dir.empty() ? default_cache_dir() : options.cache_dir;
  if (options.use_cache && !dir.empty()) s.cache_path = dir + "/" + cache_file_name(key);
  // Tables in memory already: the same key gives the same tables (the key holds every parameter
  // and the table layout), whichever cache folder they came from.
  if (options.use_cache && options.share_in_process) {
    LiveTables& live = live_tables();
    const std::lock_guard<std::mutex> lock(live.mutex);
    const auto it = live.by_key.find(key);
    if (it != live.by_key.end()) {
      if (auto tables = it->second.lock()) {
        s.tables = std::move(tables);
        s.cache_status = "shared";
        return model;
      }
    }
  }
  auto register_tables = [&] {
    if (!options.use_cache) return;
    LiveTables& live = live_tables();
    const std::lock_guard<std::mutex> lock(live.mutex);
    for (auto it = live.by_key.begin(); it != live.by_key.end();)  // forget expired entries
      it = it->second.expired() ? live.by_key.erase(it) : std::next(it);
    live.by_key[key] = s.tables;
  };

  auto tables = std::make_shared<ModelTables>();
  if (!s.cache_path.empty()) {
    const auto start = std::chrono::steady_clock::now();
    if (load_cache(s.cache_path, key, *tables)) {
      s.load_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      s.cache_status = "loaded";
      s.tables = std::move(tables);
      register_tables();
      return model;
    }
  }

  int threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  if (threads < 1) threads = 1;
  const auto start = std::chrono::steady_clock::now();
  precompute_tables(parameters, threads, *tables);
  s.precompute_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (!options.use_cache) {
    s.cache_status = "computed (cache disabled)";
  } else if (dir.empty()) {
    s.cache_status = "computed (no cache folder: set THALASSA_CACHE_DIR or HOME)";
  } else {
    const std::string error = store_cache(s.cache_path, key, *tables);
    s.cache_status = error.empty() ? "computed" : "computed (cache not written: " + error + ")";
  }
  s.tables = std::move(tables);
  register_tables();
  return model;
}

const AtmosphereParameters& AtmosphereModel::parameters() const { return state_->parameters; }
double AtmosphereModel::precompute_seconds() const { return state_->precompute_seconds; }
double AtmosphereModel::load_seconds() const { return state_->load_seconds; }
const std::string& AtmosphereModel::cache_status() const { return state_->cache_status; }
const std::string& AtmosphereModel::cache_path() const { return state_->cache_path; }
const ModelTables& AtmosphereModel::tables() const { return *state_->tables; }

glm::dvec3 AtmosphereModel::sky_radiance(const glm::dvec3& camera, const glm::dvec3& view,
                                         const glm::dvec3& sun_direction,
                                         glm::dvec3* transmittance) const {
  glsl::vec3 t;
  const glsl::vec3 l = glsl::GetSkyRadiance(
      state_->atmosphere, state_->tables->transmittance, state_->tables->scattering,
      state_->tables->single_mie_scattering, dv(camera), dv(view), dv(sun_direction), t);
  if (transmittance) *transmittance = t;
  return l;
}

glm::dvec3 AtmosphereModel::sky_radiance_to_point(const glm::dvec3& camera, const glm::dvec3& point,
                                                  const glm::dvec3& sun_direction,
                                                  glm::dvec3* transmittance) const {
  glsl::vec3 t;
  const glsl::vec3 l = glsl::GetSkyRadianceToPoint(
      state_->atmosphere, state_->tables->transmittance, state_->tables->scattering,
      state_->tables->single_mie_scattering, dv(camera), dv(point), dv(sun_direction), t);
  if (transmittance) *transmittance = t;
  return l;
}

glm::dvec3 AtmosphereModel::sun_transmittance(const glm::dvec3& point,
                                              const glm::dvec3& sun_direction) const {
  const double r = glm::length(point);
  const double mu_s = glm::clamp(glm::dot(point, sun_direction) / r, -1.0, 1.0);
  return glsl::GetTransmittanceToSun(state_->atmosphere, state_->tables->transmittance,
                                     glsl::ClampRadius(state_->atmosphere, r), mu_s);
}

glm::dvec3 AtmosphereModel::sun_radiance(const glm::dvec3& point,
                                         const glm::dvec3& sun_direction) const {
  const double alpha = state_->parameters.sun_angular_radius;
  const double solid_angle = 2.0 * glsl::PI * (1.0 - std::cos(alpha));
  return state_->parameters.solar_irradiance / solid_angle *
         sun_transmittance(point, sun_direction);
}

glm::dvec3 AtmosphereModel::sun_and_sky_irradiance(const glm::dvec3& point,
                                                   const glm::dvec3& normal,
                                                   const glm::dvec3& sun_direction,
                                                   glm::dvec3* sky_irradiance) const {
  glsl::vec3 sky;
  const glsl::vec3 sun = glsl::GetSunAndSkyIrradiance(
      state_->atmosphere, state_->tables->transmittance, state_->tables->irradiance, dv(point),
      dv(normal), dv(sun_direction), sky);
  if (sky_irradiance) *sky_irradiance = sky;
  return sun;
}

}  // namespace thalassa::atmosphere
