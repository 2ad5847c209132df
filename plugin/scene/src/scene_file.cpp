// Scene files: JSON read with nlohmann-json, every object checked key by key (a typo is an
// error, never ignored), every value by type and range, every reference by name.
#include "adb/scene/scene_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include "adb/io/message_text.h"
#include "adb/scene/scene_models.h"

namespace adb::scene {

SceneError::SceneError(std::string file, std::string where, const std::string& what)
    : std::runtime_error(file + ": " + (where.empty() ? "" : where + ": ") + what),
      m_file(std::move(file)),
      m_where(std::move(where)) {}

namespace {

// ordered_json: objects keep the file's order (shapes, and the first error in reading order).
using Json = nlohmann::ordered_json;

const char* typeName(const Json& j) {
  switch (j.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return "a boolean";
    case Json::value_t::string: return "a string";
    case Json::value_t::array: return "an array";
    case Json::value_t::object: return "an object";
    case Json::value_t::discarded: return "nothing";
    default: return "a number";
  }
}

// What the file wrote, quoted short and printable (adb/io/message_text.h): a damaged or hostile
// file can hold a name of megabytes.
std::string inQuotes(const std::string& s) { return io::quoted(s); }
std::string keyText(const std::string& key) { return io::excerpt(key, 60); }

// The first ten names, then how many more.
std::string joined(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 10;
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < kShown; ++i) {
    out += (out.empty() ? "" : ", ") + keyText(names[i]);
  }
  if (names.size() > kShown) out += " and " + std::to_string(names.size() - kShown) + " more";
  return out;
}

// One JSON object being read: each key is taken once, and finish() refuses the rest (a key
// nobody asked for is a typo or a feature this version does not have).
class Object {
 public:
  Object(const Json& json, std::string path, const std::string& file)
      : m_json(json), m_path(std::move(path)), m_file(file) {
    if (!json.is_object()) fail(m_path, std::string("expected an object, got ") + typeName(json));
  }

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw SceneError(m_file, where, what);
  }
  std::string at(const std::string& key) const {
    return m_path.empty() ? keyText(key) : m_path + "." + keyText(key);
  }
  bool has(const std::string& key) const { return m_json.contains(key); }

  // The value under `key` (marked as read), or nullptr when absent.
  const Json* find(const std::string& key) {
    const auto it = m_json.find(key);
    if (it == m_json.end()) return nullptr;
    m_read.push_back(key);
    return &*it;
  }
  const Json& require(const std::string& key) {
    const Json* j = find(key);
    if (!j) fail(m_path, "missing key " + inQuotes(key));
    return *j;
  }

  double number(const std::string& key, double fallback, double lo, double hi) {
    const Json* j = find(key);
    if (!j) return fallback;
    return numberAt(*j, at(key), lo, hi);
  }
  double numberAt(const Json& j, const std::string& where, double lo, double hi) const {
    if (!j.is_number()) fail(where, std::string("expected a number, got ") + typeName(j));
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < lo || v > hi) {
      std::ostringstream s;
      s << v << " is out of range [" << lo << ", " << hi << "]";
      fail(where, s.str());
    }
    return v;
  }
  std::int64_t integer(const std::string& key, std::int64_t fallback, std::int64_t lo,
                       std::int64_t hi) {
    const Json* j = find(key);
    if (!j) return fallback;
    if (!j->is_number_integer()) {
      fail(at(key), std::string("expected an integer, got ") + typeName(*j));
    }
    const std::int64_t v = j->get<std::int64_t>();
    if (v < lo || v > hi) {
      fail(at(key), std::to_string(v) + " is out of range [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
    }
    return v;
  }
  bool boolean(const std::string& key, bool fallback) {
    const Json* j = find(key);
    if (!j) return fallback;
    if (!j->is_boolean()) fail(at(key), std::string("expected a boolean, got ") + typeName(*j));
    return j->get<bool>();
  }
  std::string string(const std::string& key) {
    const Json& j = require(key);
    if (!j.is_string()) fail(at(key), std::string("expected a string, got ") + typeName(j));
    return j.get<std::string>();
  }
  std::string string(const std::string& key, const std::string& fallback) {
    return has(key) ? string(key) : fallback;
  }
  Vec3 vec3(const std::string& key, const Vec3& fallback) {
    const Json* j = find(key);
    return j ? vec3At(*j, at(key)) : fallback;
  }
  Vec3 vec3At(const Json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 3) {
      fail(where, std::string("expected an array of 3 numbers, got ") +
                      (j.is_array() ? "an array of " + std::to_string(j.size()) : typeName(j)));
    }
    const double inf = std::numeric_limits<double>::max();
    return Vec3(numberAt(j[0], where + "[0]", -inf, inf), numberAt(j[1], where + "[1]", -inf, inf),
                numberAt(j[2], where + "[2]", -inf, inf));
  }

  void finish() const {
    for (auto it = m_json.begin(); it != m_json.end(); ++it) {
      if (std::find(m_read.begin(), m_read.end(), it.key()) == m_read.end()) {
        fail(at(it.key()), "unknown key " + inQuotes(it.key()));
      }
    }
  }
  const std::string& path() const { return m_path; }
  const std::string& file() const { return m_file; }

 private:
  const Json& m_json;
  std::string m_path;
  const std::string& m_file;
  std::vector<std::string> m_read;
};

constexpr double kInf = std::numeric_limits<double>::max();
constexpr double kPi = 3.14159265358979323846;

// A pose: "position" [x, y, z] and at most one of "quaternion" [w, x, y, z] (normalised) or
// "axis_angle" {"axis": [x, y, z], "degrees": d}.
Pose readPose(Object& o) {
  Pose pose;
  pose.translation = o.vec3("position", Vec3::Zero());
  if (o.has("quaternion") && o.has("axis_angle")) {
    o.fail(o.path(), "give either 'quaternion' or 'axis_angle', not both");
  }
  if (const Json* q = o.find("quaternion")) {
    const std::string where = o.at("quaternion");
    if (!q->is_array() || q->size() != 4) o.fail(where, "expected [w, x, y, z]");
    const Eigen::Quaterniond r(o.numberAt((*q)[0], where + "[0]", -kInf, kInf),
                               o.numberAt((*q)[1], where + "[1]", -kInf, kInf),
                               o.numberAt((*q)[2], where + "[2]", -kInf, kInf),
                               o.numberAt((*q)[3], where + "[3]", -kInf, kInf));
    if (!(r.norm() > 1e-9) || !std::isfinite(r.norm())) o.fail(where, "a zero quaternion");
    pose.rotation = r.normalized().toRotationMatrix();
  }
  if (const Json* a = o.find("axis_angle")) {
    Object aa(*a, o.at("axis_angle"), o.file());
    const Vec3 axis = aa.vec3At(aa.require("axis"), aa.at("axis"));
    const double degrees = aa.numberAt(aa.require("degrees"), aa.at("degrees"), -kInf, kInf);
    aa.finish();
    if (!(axis.norm() > 1e-12) || !std::isfinite(axis.norm())) aa.fail(aa.at("axis"), "a zero axis");
    pose.rotation = Eigen::AngleAxisd(degrees * kPi / 180.0, axis.normalized()).toRotationMatrix();
  }
  return pose;
}

WorldSpec readWorld(const Json& j, const std::string& file) {
  Object o(j, "world", file);
  WorldSpec w;
  w.gravity = o.vec3("gravity", w.gravity);
  w.timeStep = o.number("time_step", w.timeStep, 1e-6, 1.0);
  w.steps = static_cast<int>(o.integer("steps", w.steps, 1, 100000000));
  w.substeps = static_cast<int>(o.integer("substeps", w.substeps, 1, 1000));
  w.pMin = o.number("p_min", w.pMin, 0.0, 1.0);
  w.kMin = static_cast<int>(o.integer("k_min", w.kMin, 0, 1000000));
  w.pAccept = o.number("p_accept", w.pAccept, 0.0, 1.0);
  w.threads = static_cast<int>(o.integer("threads", w.threads, 0, kMaxThreads));
  w.keepRestingContacts = o.boolean("keep_resting_contacts", w.keepRestingContacts);
  w.auditContacts = o.boolean("audit_contacts", w.auditContacts);
  const std::string fronts = o.string("fronts", kFrontsNames[0]);
  if (const std::optional<FrameSettings::Fronts> named = frontsNamed(fronts)) {
    w.fronts = *named;
  } else {
    o.fail(o.at("fronts"), "'" + fronts + "' is not one of " +
                               joined({kFrontsNames.begin(), kFrontsNames.end()}));
  }
  if (const Json* b = o.find("bounds")) {
    Object bounds(*b, o.at("bounds"), file);
    Aabb box;
    box.lo = bounds.vec3At(bounds.require("min"), bounds.at("min"));
    box.hi = bounds.vec3At(bounds.require("max"), bounds.at("max"));
    if (!(box.lo.array() < box.hi.array()).all()) {
      bounds.fail(bounds.at("max"), "must exceed 'min' on every axis");
    }
    bounds.finish();
    w.bounds = box;
  }
  if (const Json* b = o.find("budget")) {
    Object budget(*b, o.at("budget"), file);
    if (budget.has("micros") && budget.has("node_pairs")) {
      budget.fail(budget.path(), "give either 'micros' or 'node_pairs', not both");
    }
    if (budget.has("micros")) {
      w.budget.kind = BudgetSpec::Kind::Micros;
      w.budget.micros = budget.number("micros", 0.0, 0.0, 1e9);
    } else if (budget.has("node_pairs")) {
      w.budget.kind = BudgetSpec::Kind::NodePairs;
      w.budget.nodePairs = static_cast<std::uint64_t>(
          budget.integer("node_pairs", 0, 0, std::numeric_limits<std::int64_t>::max()));
    } else {
      budget.fail(budget.path(), "expected 'micros' or 'node_pairs'");
    }
    budget.finish();
  }
  o.finish();
  return w;
}

const std::vector<std::string> kShapeKinds = {"mesh", "generated", "box", "sphere", "capsule",
                                              "plane"};

void readHalfExtents(Object& o, ShapeSpec& s) {
  s.halfExtents = o.vec3At(o.require("half_extents"), o.at("half_extents"));
  if (!(s.halfExtents.array() > 0.0).all()) o.fail(o.at("half_extents"), "must be positive");
}

ViewSpec readView(const Json& j, const std::string& file) {
  Object o(j, "view", file);
  ViewSpec v;
  v.given = true;
  v.eye = o.vec3At(o.require("eye"), o.at("eye"));
  v.target = o.vec3At(o.require("target"), o.at("target"));
  if (!((v.target - v.eye).norm() > 0)) o.fail(o.at("target"), "the same point as the eye");
  v.fovDegrees = o.number("fov_degrees", v.fovDegrees, 1.0, 170.0);
  o.finish();
  return v;
}

ShapeSpec readShape(const std::string& name, const Json& j, const std::string& file,
                    const std::filesystem::path& folder, const GivenMeshes& meshes) {
  Object o(j, "shapes." + keyText(name), file);
  ShapeSpec s;
  s.name = name;
  const std::string kind = o.string("type");
  if (kind == "mesh") {
    s.kind = ShapeSpec::Kind::Mesh;
    const auto inCode = meshes.find(name);
    if (inCode != meshes.end() && !o.has("file")) {
      s.given = inCode->second;
    } else {
      const std::filesystem::path given = o.string("file");
      s.file = given.is_absolute() ? given : folder / given;
      std::error_code error;
      if (!std::filesystem::is_regular_file(s.file, error)) {
        o.fail(o.at("file"), "no mesh file " + inQuotes(s.file.string()));
      }
    }
    if (o.has("size") && (o.has("scale") || o.has("recentre"))) {
      o.fail(o.at("size"), "give either 'size' or 'scale' and 'recentre', not both");
    }
    s.size = o.number("size", 0.0, 1e-12, 1e12);
    s.scale = o.number("scale", 1.0, 1e-12, 1e12);
    s.recentre = o.boolean("recentre", true);
  } else if (kind == "generated") {
    s.kind = ShapeSpec::Kind::Generated;
    s.model = o.string("model");
    const std::vector<std::string> models = generatedModelNames();
    if (std::find(models.begin(), models.end(), s.model) == models.end()) {
      o.fail(o.at("model"), "unknown model " + inQuotes(s.model) + " (known: " + joined(models) + ")");
    }
    s.triangles = static_cast<std::size_t>(o.integer("triangles", 2000, 12, 10000000));
    s.scale = o.number("scale", 1.0, 1e-12, 1e12);
    if (s.model == "gear") s.teeth = static_cast<int>(o.integer("teeth", s.teeth, 3, 400));
    if (s.model == "box") readHalfExtents(o, s);
  } else if (kind == "box") {
    s.kind = ShapeSpec::Kind::Box;
    readHalfExtents(o, s);
  } else if (kind == "sphere") {
    s.kind = ShapeSpec::Kind::Sphere;
    s.radius = o.numberAt(o.require("radius"), o.at("radius"), 1e-12, 1e12);
  } else if (kind == "capsule") {
    s.kind = ShapeSpec::Kind::Capsule;
    s.radius = o.numberAt(o.require("radius"), o.at("radius"), 1e-12, 1e12);
    s.height = o.numberAt(o.require("height"), o.at("height"), 0.0, 1e12);
  } else if (kind == "plane") {
    s.kind = ShapeSpec::Kind::Plane;
    const Vec3 n = o.vec3("normal", Vec3::UnitY());
    if (!(n.norm() > 1e-12)) o.fail(o.at("normal"), "a zero normal");
    s.normal = n.normalized();
    s.offset = o.number("offset", 0.0, -kInf, kInf);
  } else {
    o.fail(o.at("type"), "unknown shape type " + inQuotes(kind) + " (known: " + joined(kShapeKinds) + ")");
  }
  o.finish();
  return s;
}

BodySpec readBody(std::size_t i, const Json& j, const Scene& scene, const std::string& file) {
  Object o(j, "bodies[" + std::to_string(i) + "]", file);
  BodySpec b;
  b.name = o.string("name", "body" + std::to_string(i));
  const std::string shape = o.string("shape");
  const auto it = std::find_if(scene.shapes.begin(), scene.shapes.end(),
                               [&](const ShapeSpec& s) { return s.name == shape; });
  if (it == scene.shapes.end()) {
    std::vector<std::string> names;
    for (const ShapeSpec& s : scene.shapes) names.push_back(s.name);
    o.fail(o.at("shape"), "unknown shape " + inQuotes(shape) + " (shapes: " + joined(names) + ")");
  }
  b.shape = static_cast<std::size_t>(it - scene.shapes.begin());
  const std::string kind = o.string("kind", "dynamic");
  if (kind == "static") {
    b.kind = BodySpec::Kind::Static;
  } else if (kind == "dynamic") {
    b.kind = BodySpec::Kind::Dynamic;
  } else if (kind == "kinematic") {
    b.kind = BodySpec::Kind::Kinematic;
  } else {
    o.fail(o.at("kind"), "unknown kind " + inQuotes(kind) + " (known: static, dynamic, kinematic)");
  }
  if (o.has("mass")) {
    if (b.kind != BodySpec::Kind::Dynamic) o.fail(o.at("mass"), "only a dynamic body has a mass");
    const double mass = o.numberAt(*o.find("mass"), o.at("mass"), -kInf, kInf);
    if (!(mass > 0.0)) o.fail(o.at("mass"), "must be positive, got " + std::to_string(mass));
    b.mass = mass;
  }
  if (it->kind == ShapeSpec::Kind::Plane && b.kind != BodySpec::Kind::Static) {
    o.fail(o.at("kind"), "a plane can only be static");
  }
  const std::string poseOf = o.string("pose_of", "mesh");
  if (poseOf == "centre_of_mass") {
    const bool mesh = it->kind == ShapeSpec::Kind::Mesh || it->kind == ShapeSpec::Kind::Generated;
    if (b.kind != BodySpec::Kind::Dynamic || !mesh) {
      o.fail(o.at("pose_of"), "only a dynamic mesh body has a centre of mass to place");
    }
    b.poseOf = BodySpec::PoseOf::CentreOfMass;
  } else if (poseOf != "mesh") {
    o.fail(o.at("pose_of"), inQuotes(poseOf) + " is not one of mesh, centre_of_mass");
  }
  b.pose = readPose(o);
  b.velocity = o.vec3("velocity", Vec3::Zero());
  b.angularVelocity = o.vec3("angular_velocity", Vec3::Zero());
  b.friction = o.number("friction", b.friction, 0.0, 1e6);
  b.restitution = o.number("restitution", b.restitution, 0.0, 1.0);
  if (const Json* hinge = o.find("hinge")) {
    if (b.kind != BodySpec::Kind::Dynamic) o.fail(o.at("hinge"), "only a dynamic body has one");
    Object h(*hinge, o.at("hinge"), file);
    const Vec3 axis = h.vec3At(h.require("axis"), h.at("axis"));
    if (!(axis.norm() > 1e-12)) h.fail(h.at("axis"), "a zero axis");
    b.hinge = axis.normalized();
    h.finish();
  }
  o.finish();
  return b;
}

MotionSpec readMotion(std::size_t i, const Json& j, const Scene& scene, const std::string& file) {
  Object o(j, "motions[" + std::to_string(i) + "]", file);
  MotionSpec m;
  const std::string body = o.string("body");
  const auto it = std::find_if(scene.bodies.begin(), scene.bodies.end(),
                               [&](const BodySpec& b) { return b.name == body; });
  if (it == scene.bodies.end()) o.fail(o.at("body"), "unknown body " + inQuotes(body));
  if (it->kind != BodySpec::Kind::Kinematic) {
    o.fail(o.at("body"), inQuotes(body) + " is not kinematic: only kinematic bodies follow a motion");
  }
  m.body = static_cast<std::size_t>(it - scene.bodies.begin());
  if (o.has("twist") == o.has("keyframes")) {
    o.fail(o.path(), "give either 'twist' or 'keyframes'");
  }
  if (const Json* t = o.find("twist")) {
    Object twist(*t, o.at("twist"), file);
    m.linear = twist.vec3("linear", Vec3::Zero());
    m.angular = twist.vec3("angular", Vec3::Zero());
    twist.finish();
  } else {
    m.twist = false;
    const Json& keys = *o.find("keyframes");
    const std::string where = o.at("keyframes");
    if (!keys.is_array() || keys.empty()) o.fail(where, "expected a non-empty array of keyframes");
    for (std::size_t k = 0; k < keys.size(); ++k) {
      Object key(keys[k], where + "[" + std::to_string(k) + "]", file);
      Keyframe f;
      f.time = key.numberAt(key.require("time"), key.at("time"), 0.0, kInf);
      if (!m.keyframes.empty() && !(f.time > m.keyframes.back().time)) {
        key.fail(key.at("time"), "times must increase");
      }
      f.pose = readPose(key);
      key.finish();
      m.keyframes.push_back(f);
    }
  }
  o.finish();
  return m;
}

const std::vector<std::string> kEffects = {"overlap",     "contacts", "dynamics", "friction",
                                           "restitution", "sleeping", "ccd",      "soft_contacts"};

Effects readEffects(const Json& j, const std::string& file) {
  const std::string where = "effects";
  if (!j.is_array()) {
    throw SceneError(file, where, std::string("expected an array of effect names, got ") + typeName(j));
  }
  Effects e;
  int primary = 0;
  std::vector<std::string> seen;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string at = where + "[" + std::to_string(i) + "]";
    if (!j[i].is_string()) {
      throw SceneError(file, at, std::string("expected an effect name, got ") + typeName(j[i]));
    }
    const std::string name = j[i].get<std::string>();
    if (std::find(kEffects.begin(), kEffects.end(), name) == kEffects.end()) {
      throw SceneError(file, at, "unknown effect " + inQuotes(name) + " (known: " + joined(kEffects) + ")");
    }
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
      throw SceneError(file, at, "effect " + inQuotes(name) + " given twice");
    }
    seen.push_back(name);
    if (name == "overlap" || name == "contacts" || name == "dynamics") {
      ++primary;
      e.kind = name == "overlap" ? Effects::Kind::Overlap
               : name == "contacts" ? Effects::Kind::Contacts
                                    : Effects::Kind::Dynamics;
    }
    e.friction = e.friction || name == "friction";
    e.restitution = e.restitution || name == "restitution";
    e.sleeping = e.sleeping || name == "sleeping";
    e.ccd = e.ccd || name == "ccd";
    e.softContacts = e.softContacts || name == "soft_contacts";
  }
  if (primary != 1) {
    throw SceneError(file, where, "expected exactly one of 'overlap', 'contacts' or 'dynamics'");
  }
  if (e.kind != Effects::Kind::Dynamics) {
    for (const std::string& extra : seen) {
      if (extra != "overlap" && extra != "contacts") {
        throw SceneError(file, where, inQuotes(extra) + " needs 'dynamics'");
      }
    }
  }
  return e;
}

// Line and column (1-based) of a byte offset, for syntax errors.
std::string lineAndColumn(const std::string& text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < text.size() && i + 1 < byte; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's message, "[json.exception.parse_error.101] parse error at line 1, column 9:
// syntax error while parsing value - invalid literal; last read: '<token>'", without its own
// position and with only the end of the token, where the parser stopped.
std::string syntaxError(const std::string& message) {
  std::string what = message;
  const std::size_t column = what.find(", column ");
  const std::size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
  if (colon != std::string::npos) what = what.substr(colon + 2);
  const std::string syntax = "syntax error ";
  if (what.compare(0, syntax.size(), syntax) == 0) what = what.substr(syntax.size());
  const std::string lastRead = "; last read: '";
  const std::size_t read = what.find(lastRead);
  if (read == std::string::npos) return io::excerpt(what);
  std::string token = what.substr(read + lastRead.size());
  if (!token.empty() && token.back() == '\'') token.pop_back();
  constexpr std::size_t kTail = 40;
  const std::string tail = token.size() > kTail ? "..." + token.substr(token.size() - kTail) : token;
  return io::excerpt(what.substr(0, read)) + "; last read: '" + io::excerpt(tail) + "'";
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& name,
                 const std::filesystem::path& folder, const GivenMeshes& meshes) {
  Json json;
  try {
    json = Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw SceneError(name, lineAndColumn(text, e.byte), "syntax error: " + syntaxError(e.what()));
  } catch (const Json::exception& e) {
    // A number too large for a double (1e999): no position from the parser.
    std::string what = e.what();
    const std::size_t bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    throw SceneError(name, "", io::excerpt(what));
  }
  Object top(json, "", name);
  Scene scene;
  scene.description = top.string("description", "");
  if (const Json* w = top.find("world")) scene.world = readWorld(*w, name);
  if (const Json* v = top.find("view")) scene.view = readView(*v, name);
  const Json& shapes = top.require("shapes");
  if (!shapes.is_object() || shapes.empty()) {
    throw SceneError(name, "shapes", "expected an object of named shapes");
  }
  for (auto it = shapes.begin(); it != shapes.end(); ++it) {
    scene.shapes.push_back(readShape(it.key(), it.value(), name, folder, meshes));
  }
  const Json& bodies = top.require("bodies");
  if (!bodies.is_array() || bodies.empty()) {
    throw SceneError(name, "bodies", "expected a non-empty array of bodies");
  }
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    scene.bodies.push_back(readBody(i, bodies[i], scene, name));
    for (std::size_t k = 0; k < i; ++k) {
      if (scene.bodies[k].name == scene.bodies[i].name) {
        throw SceneError(name, "bodies[" + std::to_string(i) + "].name",
                         "name " + inQuotes(scene.bodies[i].name) + " already used by bodies[" +
                             std::to_string(k) + "]");
      }
    }
  }
  if (const Json* m = top.find("motions")) {
    if (!m->is_array()) throw SceneError(name, "motions", "expected an array of motions");
    for (std::size_t i = 0; i < m->size(); ++i) {
      scene.motions.push_back(readMotion(i, (*m)[i], scene, name));
    }
  }
  scene.effects = readEffects(top.require("effects"), name);
  top.finish();
  return scene;
}

Scene loadScene(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file.string(), "", "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  Scene scene = parseScene(text.str(), file.string(), file.parent_path());
  scene.file = file;
  return scene;
}

}  // namespace adb::scene
