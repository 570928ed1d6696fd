// Reading and validating an "mpm" case: every check happens here, before anything is built.
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "mpm/case_size.h"
#include "mpm/case_spec.h"
#include "mpm/footing.h"
#include "mpm/shape_function.h"

namespace mpm_lig::mpm {

bool Box::contains(const double* x, int dimension, double tolerance) const {
  for (int d = 0; d < dimension; ++d) {
    if (x[d] < min[d] - tolerance || x[d] > max[d] + tolerance)
      return false;
  }
  return true;
}

namespace {

const std::vector<std::string> kAxes = {"x", "y", "z"};

//! Bounds on lengths that keep the arithmetic far from overflow and denormals: cells of a
//! micrometre (below any grain-scale model) to meshes of a thousand kilometres.
constexpr double kMinCellLength = 1e-6;
constexpr double kMaxMeshLength = 1e6;
//! Bounds on loads and motions, far beyond any geomechanical problem, so that an absurd value
//! is refused by --validate instead of overflowing in the run: accelerations of 1e4 g
//! (centrifuges reach a few hundred), speeds of 10 km/s (faster than any wave in soil or
//! rock), stresses of 1e12 Pa (a thousand times the strength of rock).
constexpr double kMaxAcceleration = 1e5;
constexpr double kMaxSpeed = 1e4;
constexpr double kMaxStress = 1e12;

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::vector<std::string> axes(int dimension) {
  return {kAxes.begin(), kAxes.begin() + dimension};
}

int read_axis(const CaseNode& node, const std::string& key, int dimension) {
  const std::string name = node.choice(key, axes(dimension));
  return static_cast<int>(std::find(kAxes.begin(), kAxes.end(), name) - kAxes.begin());
}

std::vector<double> read_vector(const CaseNode& node, const std::string& key, std::size_t size) {
  const auto v = node.get<std::vector<double>>(key);
  if (v.size() != size) {
    node.fail(key, "expected " + std::to_string(size) + " numbers (one per axis), got " +
                       std::to_string(v.size()));
  }
  return v;
}

//! `value` (at `key` of `node`, component `component` or -1 for a scalar) within ±limit.
void require_within(const CaseNode& node, const std::string& key, double value, double limit,
                    const char* unit, int component = -1) {
  if (std::abs(value) <= limit)
    return;
  const std::string where = component < 0 ? "" : " (component " + std::to_string(component) + ")";
  node.fail(key,
            "must be within ±" + number(limit) + " " + unit + where + ", got " + number(value));
}

//! read_vector with every component within ±limit.
std::vector<double> read_bounded_vector(const CaseNode& node, const std::string& key,
                                        std::size_t size, double limit, const char* unit) {
  const std::vector<double> v = read_vector(node, key, size);
  for (std::size_t i = 0; i < v.size(); ++i)
    require_within(node, key, v[i], limit, unit, static_cast<int>(i));
  return v;
}

//! A box; `flat` allows min = max along an axis (a line or plane of nodes).
Box read_box(const CaseNode& node, const std::string& key, int dimension, bool flat = false) {
  const CaseNode b = node.child(key);
  Box box{read_vector(b, "min", dimension), read_vector(b, "max", dimension)};
  for (int d = 0; d < dimension; ++d) {
    if (box.min[d] > box.max[d] || (!flat && box.min[d] == box.max[d]))
      b.fail("max", std::string("must be greater than ") + (flat ? "or equal to " : "") +
                        "min along " + kAxes[d]);
  }
  return box;
}

//! A box that must lie inside the grid.
Box read_box_in_grid(const CaseNode& node, const std::string& key, const MpmCase& c) {
  Box box = read_box(node, key, c.dimension);
  for (int d = 0; d < c.dimension; ++d) {
    const double tol = 1e-9 * c.size[d];
    if (box.min[d] < c.origin[d] - tol || box.max[d] > c.origin[d] + c.size[d] + tol)
      node.child(key).fail("lies outside the mesh along " + kAxes[d]);
  }
  return box;
}

void read_internal_length(const CaseNode& l, MpmCase& c) {
  c.internal_length = l.in_range("length", kMinCellLength, kMaxMeshLength);
  c.internal_length_method =
      l.choice_or("method", {"second_gradient", "nonlocal"}, "second_gradient");
  const bool second_gradient = c.internal_length_method == "second_gradient";
  for (const char* other :
       second_gradient
           ? std::vector<const char*>{"nonlocal_weight"}
           : std::vector<const char*>{"softening_modulus", "yield_strain", "residual_weight"}) {
    if (l.has(other))
      l.fail(other, std::string("belongs to method \"") +
                        (second_gradient ? "nonlocal" : "second_gradient") + "\"");
  }
  if (second_gradient) {
    c.softening_modulus = l.in_range("softening_modulus", 1e-6, 1e15);
    if (l.has("yield_strain")) {
      c.gradient_yield_strain = l.in_range("yield_strain", 1e-6, 10.0);
      if (c.dimension != 2)
        l.fail("yield_strain", "is implemented in 2D only");
    }
    c.gradient_residual_weight = l.in_range_or("residual_weight", 0.0, 100.0, 0.0);
  } else
    c.nonlocal_weight = l.in_range_or("nonlocal_weight", 0.0, 2.0, 1.0);
}

void read_analysis(const CaseNode& a, MpmCase& c) {
  c.musl = a.choice_or("scheme", {"musl", "usl"}, "musl") == "musl";
  c.shape_function = a.choice_or("shape_function", shape_registry().names(), "linear");
  c.flip = a.in_range_or("flip", 0.0, 1.0, 1.0);
  c.damping = a.in_range_or("damping", 0.0, 0.9, 0.0);
  c.mass_scaling = a.get_or<double>("mass_scaling", 1.0);
  if (c.mass_scaling < 1.0)
    a.fail("mass_scaling", "must be >= 1");
  c.volumetric_smoothing = a.get_or<bool>("volumetric_smoothing", false);
  if (a.has("internal_length"))
    read_internal_length(a.child("internal_length"), c);

  const CaseNode ts = a.child("time_step");
  if (ts.has("fixed") == ts.has("cfl"))
    ts.fail("give exactly one of \"cfl\" or \"fixed\"");
  c.fixed_time_step = ts.has("fixed");
  if (c.fixed_time_step)
    c.time_step = ts.positive("fixed");
  else
    c.cfl = ts.in_range("cfl", 1e-6, 1.0);

  const CaseNode end = a.child("end");
  if (end.has("time") == end.has("steps"))
    end.fail("give exactly one of \"time\" or \"steps\"");
  if (end.has("time"))
    c.end_time = end.in_range("time", 1e-12, 1e12);
  else if ((c.end_steps = end.get<long>("steps")) < 1)
    end.fail("steps", "must be >= 1");

  if (a.has("gravity_stage")) {
    const CaseNode g = a.child("gravity_stage");
    if ((c.gravity_stage_steps = g.get<long>("steps")) < 1)
      g.fail("steps", "must be >= 1");
    c.gravity_stage_damping = g.in_range_or("damping", 0.0, 0.9, 0.1);
  }
}

void read_mesh(const CaseNode& m, MpmCase& c) {
  c.origin = read_vector(m, "origin", c.dimension);
  c.size = read_vector(m, "size", c.dimension);
  const auto cells = m.get<std::vector<int>>("cells");
  if (cells.size() != static_cast<std::size_t>(c.dimension))
    m.fail("cells", "expected " + std::to_string(c.dimension) + " integers (one per axis)");
  for (int d = 0; d < c.dimension; ++d) {
    if (!(c.size[d] > 0.0 && c.size[d] <= kMaxMeshLength))
      m.fail("size", "must be in (0, " + number(kMaxMeshLength) + "] m along " + kAxes[d]);
    if (!(std::abs(c.origin[d]) <= kMaxMeshLength))
      m.fail("origin", "must be within " + number(kMaxMeshLength) + " m of 0 along " + kAxes[d]);
    if (cells[d] < 1 || cells[d] > 100000)
      m.fail("cells", "must be between 1 and 100000 along " + kAxes[d]);
    if (!(c.size[d] / cells[d] >= kMinCellLength))
      m.fail("size", "cells of " + number(c.size[d] / cells[d]) + " m along " + kAxes[d] +
                         " are smaller than " + number(kMinCellLength) + " m");
  }
  c.cells = cells;
  c.periodic.assign(c.dimension, false);
  if (!m.has("periodic"))
    return;
  const std::vector<std::string> names = m.get<std::vector<std::string>>("periodic");
  const std::vector<std::string> valid = axes(c.dimension);
  for (const std::string& name : names) {
    const auto it = std::find(valid.begin(), valid.end(), name);
    if (it == valid.end())
      m.fail("periodic",
             "'" + name + "' is not an axis of this " + std::to_string(c.dimension) + "D mesh");
    const std::size_t d = static_cast<std::size_t>(it - valid.begin());
    if (c.periodic[d])
      m.fail("periodic", "axis " + name + " is given twice");
    if (d + 1 == static_cast<std::size_t>(c.dimension))
      m.fail("periodic", "the last axis (vertical: gravity, footings) cannot be periodic");
    c.periodic[d] = true;
  }
}

void read_materials(const CaseNode& root, const materials::MaterialRegistry& registry, MpmCase& c,
                    MaterialSet& materials) {
  materials.set_zero_statistics(registry.statistics());
  const auto nodes = root.children("materials");
  if (nodes.empty())
    root.fail("materials", "needs at least one material");
  for (const CaseNode& m : nodes) {
    const int id = m.get<int>("id");
    if (std::count(c.material_ids.begin(), c.material_ids.end(), id) != 0)
      m.fail("id", "material id " + std::to_string(id) + " is used twice");
    c.material_ids.push_back(id);
    materials.add(registry.create(m, "type", m));
    materials[materials.size() - 1]->check_dimension(m, c.dimension);
  }
}

//! A CFL number above what a material was measured stable at is refused before anything runs.
void check_cfl(const CaseNode& root, const MpmCase& c, const MaterialSet& materials) {
  if (c.fixed_time_step)
    return;
  for (std::size_t k = 0; k < materials.size(); ++k) {
    const double limit = materials[k]->max_cfl();
    std::ostringstream text;
    text << limit;
    if (c.cfl > limit)
      root.child("analysis")
          .child("time_step")
          .fail("cfl", "must be <= " + text.str() + " with materials[" + std::to_string(k) +
                           "] (type \"" + materials[k]->type() +
                           "\"): measured unstable above it (docs/testing.md, Hard cases)");
  }
}

int material_index(const CaseNode& node, const std::string& key, const MpmCase& c) {
  const int id = node.get<int>(key);
  const auto it = std::find(c.material_ids.begin(), c.material_ids.end(), id);
  if (it == c.material_ids.end())
    node.fail(key, "no material with id " + std::to_string(id));
  return static_cast<int>(it - c.material_ids.begin());
}

bool overlap(const Box& a, const Box& b, int dimension) {
  for (int d = 0; d < dimension; ++d) {
    if (a.max[d] <= b.min[d] || b.max[d] <= a.min[d])
      return false;
  }
  return true;
}

//! A uniform start stress: Voigt xx yy zz xy xz yz [Pa], tension positive; in 2D (plane strain)
//! xz and yz must be 0.
Mat3 read_initial_stress(const CaseNode& b, int dimension) {
  const std::vector<double> v = read_bounded_vector(b, "initial_stress", 6, kMaxStress, "Pa");
  if (dimension == 2 && (v[4] != 0.0 || v[5] != 0.0))
    b.fail("initial_stress", "xz and yz must be 0 in plane strain");
  Mat3 s;
  s << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  return s;
}

void read_bodies(const CaseNode& root, MpmCase& c) {
  const auto nodes = root.children("bodies");
  if (nodes.empty())
    root.fail("bodies", "needs at least one body");
  for (const CaseNode& b : nodes) {
    Body body;
    body.material = material_index(b, "material", c);
    body.box = read_box_in_grid(b, "box", c);
    body.points_per_cell = b.get_or<int>("points_per_cell", 2);
    if (body.points_per_cell < 1 || body.points_per_cell > 6)
      b.fail("points_per_cell", "must be between 1 and 6");
    body.velocity = b.has("velocity")
                        ? read_bounded_vector(b, "velocity", c.dimension, kMaxSpeed, "m/s")
                        : std::vector<double>(c.dimension, 0.0);
    if (b.has("velocity_profile")) {
      const CaseNode p = b.child("velocity_profile");
      p.choice("type", {"axial_mode"});
      body.has_profile = true;
      body.profile_amplitude = read_bounded_vector(p, "amplitude", c.dimension, kMaxSpeed, "m/s");
      body.profile_axis = read_axis(p, "axis", c.dimension);
      body.profile_start = p.get<double>("start");
      body.profile_length = p.positive("length");
    }
    if (b.has("initial_stress"))
      body.initial_stress = read_initial_stress(b, c.dimension);
    for (std::size_t k = 0; k < c.bodies.size(); ++k) {
      if (overlap(body.box, c.bodies[k].box, c.dimension))
        b.fail("box", "overlaps bodies[" + std::to_string(k) + "]");
    }
    c.bodies.push_back(std::move(body));
  }
}

//! Whether some grid node lies in `box` (tolerance 1e-9 cell, as the solver selects them).
bool box_holds_a_node(const Box& box, const MpmCase& c) {
  for (int d = 0; d < c.dimension; ++d) {
    const double h = c.size[d] / c.cells[d], tol = 1e-9 * h;
    const double first = std::ceil((box.min[d] - tol - c.origin[d]) / h);
    const double last = std::floor((box.max[d] + tol - c.origin[d]) / h);
    if (std::max(first, 0.0) > std::min(last, static_cast<double>(c.cells[d])))
      return false;
  }
  return true;
}

//! Whether some material point lies in `box` (the points of a body are a grid; the solver
//! selects the points of a traction box with no tolerance).
bool box_holds_a_point(const Box& box, const MpmCase& c) {
  return std::any_of(c.bodies.begin(), c.bodies.end(), [&](const Body& body) {
    for (int d = 0; d < c.dimension; ++d) {
      const std::vector<double> x = point_coordinates(c, body, d);
      if (std::none_of(x.begin(), x.end(),
                       [&](double v) { return v >= box.min[d] && v <= box.max[d]; }))
        return false;
    }
    return true;
  });
}

NodeSelector read_nodes(const CaseNode& node, const MpmCase& c) {
  const CaseNode n = node.child("nodes");
  if (n.has("box") == n.has("face"))
    n.fail("give exactly one of \"box\" or \"face\"");
  NodeSelector s;
  if (n.has("box")) {
    s.box = read_box(n, "box", c.dimension, true);
    if (!box_holds_a_node(s.box, c))
      n.fail("box", "contains no grid node");
    return s;
  }
  std::vector<std::string> faces;
  for (const auto& axis : axes(c.dimension)) {
    faces.push_back(axis + "-");
    faces.push_back(axis + "+");
  }
  const std::string face = n.choice("face", faces);
  s.by_face = true;
  s.axis =
      static_cast<int>(std::find(kAxes.begin(), kAxes.end(), face.substr(0, 1)) - kAxes.begin());
  s.upper = face[1] == '+';
  if (c.periodic[s.axis])
    n.fail("face",
           "the mesh is periodic along " + kAxes[s.axis] + ": " + face + " is not a boundary");
  return s;
}

//! A rotation's fastest node, at the mesh corner farthest from its centre, within kMaxSpeed.
void require_rotation_speed(const CaseNode& b, const Constraint& k, const MpmCase& c) {
  double reach = 0.0;
  for (int corner = 0; corner < (1 << c.dimension); ++corner) {
    Vec3 r = Vec3::Zero();
    for (int d = 0; d < c.dimension; ++d)
      r[d] = c.origin[d] + ((corner >> d) & 1) * c.size[d] - k.center[d];
    reach = std::max(reach, r.norm());
  }
  const double speed = k.angular_velocity.norm() * reach;
  if (!(speed <= kMaxSpeed))
    b.fail("angular_velocity", "moves the mesh corner farthest from the centre at " +
                                   number(speed) + " m/s: at most " + number(kMaxSpeed) +
                                   " m/s (|angular_velocity| × distance)");
}

void read_boundary_conditions(const CaseNode& root, MpmCase& c) {
  if (!root.has("boundary_conditions"))
    return;
  int index = -1;
  for (const CaseNode& b : root.children("boundary_conditions")) {
    ++index;
    const std::string type =
        b.choice("type", {"fixed", "roller", "velocity", "rotation", "traction"});
    if (type == "traction") {
      Traction t;
      t.points = read_box(b, "points", c.dimension);
      t.traction = read_bounded_vector(b, "traction", c.dimension, kMaxStress, "Pa");
      const bool on_a_body = std::any_of(c.bodies.begin(), c.bodies.end(), [&](const Body& body) {
        return overlap(t.points, body.box, c.dimension);
      });
      if (!on_a_body)
        b.fail("points", "the box holds no material point (it overlaps no body)");
      if (!box_holds_a_point(t.points, c))
        b.fail("points",
               "the box holds no material point (it lies between the rows of points its body "
               "is filled with: widen it or move it onto a row)");
      t.function = TimeFunction::read(b, "function");
      c.tractions.push_back(std::move(t));
      continue;
    }
    Constraint k;
    k.case_index = index;
    k.nodes = read_nodes(b, c);
    k.type = type == "fixed"      ? Constraint::Type::fixed
             : type == "roller"   ? Constraint::Type::roller
             : type == "rotation" ? Constraint::Type::rotation
                                  : Constraint::Type::velocity;
    if (k.type == Constraint::Type::roller || k.type == Constraint::Type::velocity)
      k.direction = read_axis(b, "direction", c.dimension);
    if (k.type == Constraint::Type::rotation) {
      k.center = read_bounded_vector(b, "center", c.dimension, kMaxMeshLength, "m");
      if (c.dimension == 2) {
        k.angular_velocity.z() = b.get<double>("angular_velocity");
      } else {
        const std::vector<double> w = read_vector(b, "angular_velocity", 3);
        k.angular_velocity = Vec3(w[0], w[1], w[2]);
      }
      require_rotation_speed(b, k, c);
      k.function = TimeFunction::read(b, "function");
    }
    if (k.type == Constraint::Type::velocity) {
      k.velocity = b.get<double>("velocity");
      require_within(b, "velocity", k.velocity, kMaxSpeed, "m/s");
      k.function = TimeFunction::read(b, "function");
    }
    c.constraints.push_back(std::move(k));
  }
}

//! A footing's `contact` and, for `penalty`, its `penalty_stiffness` and
//! `penalty_edge_inset` (docs/footing_contact.md).
void read_footing_contact(const CaseNode& r, const MpmCase& c, Footing& f) {
  const bool penalty = r.choice_or("contact", {"nodes", "penalty"}, "nodes") == "penalty";
  f.contact = penalty ? Footing::Contact::penalty : Footing::Contact::nodes;
  if (!penalty) {
    for (const char* key : {"penalty_stiffness", "penalty_edge_inset", "interface_friction_deg"}) {
      if (r.has(key))
        r.fail(key, "applies to \"contact\": \"penalty\" only");
    }
    return;
  }
  // Stable with the CFL step of the soil alone while sqrt(1 + stiffness) * cfl < 2.
  f.penalty_stiffness = r.in_range_or("penalty_stiffness", 0.01, 2.0, 1.0);
  f.penalty_edge_inset = r.get_or<bool>("penalty_edge_inset", true);
  if (r.has("interface_friction_deg") && !f.rough)
    r.fail("interface_friction_deg", "applies to \"interface\": \"rough\" only");
  f.interface_friction_deg = r.in_range_or("interface_friction_deg", 0.0, 90.0, 90.0);
  for (int d = 0; f.penalty_edge_inset && d + 1 < c.dimension; ++d) {
    const double cell = c.size[d] / c.cells[d];
    const FootingSpan span =
        footing_span(f.center[d], f.width[d], c.origin[d], c.size[d], 0.5 * cell, 1e-9 * cell);
    if (!span.presses(1e-9 * cell))
      r.fail("width",
             "the penalty contact presses the footprint less half a cell at each edge "
             "inside the mesh, and this footing is too narrow for that: it would press "
             "nothing (refine the mesh, or \"penalty_edge_inset\": false)");
  }
  if (f.keep_points_out)
    r.fail("keep_points_out",
           "a penalty contact keeps the points out by itself; this moves them every step");
}

void read_rigid_bodies(const CaseNode& root, MpmCase& c) {
  if (!root.has("rigid_bodies"))
    return;
  const int h = c.dimension - 1;  // horizontal axes
  for (const CaseNode& r : root.children("rigid_bodies")) {
    r.choice("type", {"footing"});
    // A footing's footprint is cut at the mesh faces (half models): not across a seam.
    if (std::find(c.periodic.begin(), c.periodic.end(), true) != c.periodic.end())
      r.fail("type", "footings are not supported on a periodic mesh (mesh.periodic)");
    Footing f;
    f.center = read_vector(r, "center", h);
    f.width = read_vector(r, "width", h);
    int covered = 0;  // horizontal axes along which the footing spans the whole mesh
    for (int d = 0; d < h; ++d) {
      if (!(f.width[d] > 0.0))
        r.fail("width", "must be > 0");
      const double lo = f.center[d] - 0.5 * f.width[d], hi = f.center[d] + 0.5 * f.width[d];
      const double end = c.origin[d] + c.size[d], tol = 1e-9 * c.size[d];
      if (hi <= c.origin[d] || lo >= end)
        r.fail("center", "the footing lies outside the mesh along " + kAxes[d]);
      // Cut at a face (a half model) is fine, and so is a strip across a 3D slab; covering the
      // whole top is a loaded layer, not a footing.
      covered += lo <= c.origin[d] + tol && hi >= end - tol;
    }
    if (covered == h)
      r.fail("width", "the footing covers the whole top of the mesh: no soil is left beside it");
    f.base = r.get<double>("base");
    if (f.base < c.origin[h] || f.base > c.origin[h] + c.size[h])
      r.fail("base", "lies outside the mesh");
    f.velocity = r.get<double>("velocity");
    require_within(r, "velocity", f.velocity, kMaxSpeed, "m/s");
    f.function = TimeFunction::read(r, "function");
    f.rough = r.choice("interface", {"rough", "smooth"}) == "rough";
    f.keep_points_out = r.get_or<bool>("keep_points_out", false);
    read_footing_contact(r, c, f);
    c.footings.push_back(std::move(f));
  }
}

//! output.simple_shear: {"material": id, "boundary_condition": k}, k a velocity constraint
//! with a periodic time function (its period counts the cycles).
void read_simple_shear(const CaseNode& o, MpmCase& c) {
  if (!o.has("simple_shear"))
    return;
  const CaseNode s = o.child("simple_shear");
  SimpleShearOutput& out = c.simple_shear;
  out.enabled = true;
  out.material = material_index(s, "material", c);
  if (std::none_of(c.bodies.begin(), c.bodies.end(),
                   [&](const Body& b) { return b.material == out.material; }))
    s.fail("material", "no body is made of this material");
  const int index = s.get<int>("boundary_condition");
  const auto driver = std::find_if(c.constraints.begin(), c.constraints.end(),
                                   [&](const Constraint& k) { return k.case_index == index; });
  if (driver == c.constraints.end() || driver->type != Constraint::Type::velocity)
    s.fail("boundary_condition", "must be the index of a \"velocity\" boundary condition");
  const TimeFunction::Kind kind = driver->function.kind;
  if (kind == TimeFunction::Kind::constant || kind == TimeFunction::Kind::ramp)
    s.fail("boundary_condition",
           "its function must be periodic (triangular, square or sine) to count cycles");
  out.period = driver->function.time;
}

//! output.rve_snapshots: {"at": [[x, y], ...], "every": n}; every position must lie in a body
//! whose material has a microstructure (dem_rve).
void read_rve_snapshots(const CaseNode& o, MpmCase& c, const MaterialSet& materials) {
  if (!o.has("rve_snapshots"))
    return;
  const CaseNode s = o.child("rve_snapshots");
  RveSnapshotOutput& out = c.rve_snapshots;
  if ((out.every = s.get_or<long>("every", 0)) < 0)
    s.fail("every", "must be >= 0 (0: first and last step only)");
  const std::vector<CaseNode> at = s.children("at");
  if (at.empty())
    s.fail("at", "needs at least one position");
  for (std::size_t i = 0; i < at.size(); ++i) {
    const std::string key = "at[" + std::to_string(i) + "]";
    const nlohmann::json& v = at[i].json();
    if (!v.is_array() || v.size() != static_cast<std::size_t>(c.dimension) ||
        !std::all_of(v.begin(), v.end(), [](const nlohmann::json& x) { return x.is_number(); }))
      s.fail(key, "expected " + std::to_string(c.dimension) + " numbers (a position)");
    const std::vector<double> x = v.get<std::vector<double>>();
    const bool on_dem = std::any_of(c.bodies.begin(), c.bodies.end(), [&](const Body& b) {
      return materials::has_snapshots(*materials[b.material]) &&
             b.box.contains(x.data(), c.dimension, 0.0);
    });
    if (!on_dem)
      s.fail(key, "lies in no body of a dem_rve material");
    out.at.push_back(x);
  }
}

void read_output(const CaseNode& root, MpmCase& c, const MaterialSet& materials) {
  if (!root.has("output"))
    return;
  const CaseNode o = root.child("output");
  if ((c.output_every = o.get_or<long>("every", 100)) < 1)
    o.fail("every", "must be >= 1");
  if ((c.history_every = o.get_or<long>("history_every", 1)) < 1)
    o.fail("history_every", "must be >= 1");
  c.write_fields = o.get_or<bool>("fields", true);
  c.write_deformation = o.get_or<bool>("deformation_gradient", false);
  if (c.write_deformation && !c.write_fields)
    o.fail("deformation_gradient", "is written into results.h5, which output.fields turns off");
  c.record_damping_work = o.get_or<bool>("damping_work", false);
  read_simple_shear(o, c);
  read_rve_snapshots(o, c, materials);
  if ((c.checkpoint_every = o.get_or<long>("checkpoint_every", 0)) < 0)
    o.fail("checkpoint_every", "must be >= 0 (0: checkpoints on SIGTERM/SIGINT only)");
  for (std::size_t k = 0; k < materials.size(); ++k) {
    // A checkpoint saves each point's stress; a DEM point's RVE saves its own state.
    const auto* m = materials[k];
    if (c.checkpoint_every > 0 && !m->checkpointable())
      o.fail("checkpoint_every", "material type '" + m->type() +
                                     "' has state variables a checkpoint does not save yet");
  }
}

}  // namespace

MpmProblem read_case(const CaseNode& root, const materials::MaterialRegistry& registry) {
  MpmProblem problem;
  MpmCase& c = problem.spec;
  c.document = root.json();
  c.title = root.get_or<std::string>("title", "");
  c.dimension = root.get<int>("dimension");
  if (c.dimension != 2 && c.dimension != 3)
    root.fail("dimension", "must be 2 (plane strain) or 3");
  read_analysis(root.child("analysis"), c);
  read_mesh(root.child("mesh"), c);
  c.gravity = root.has("gravity")
                  ? read_bounded_vector(root, "gravity", c.dimension, kMaxAcceleration, "m/s²")
                  : std::vector<double>(c.dimension, 0.0);
  read_materials(root, registry, c, problem.materials);
  check_cfl(root, c, problem.materials);
  read_bodies(root, c);
  const auto body_nodes = root.children("bodies");
  for (std::size_t k = 0; k < c.bodies.size(); ++k) {
    const materials::Material& m = *problem.materials[c.bodies[k].material];
    if (c.bodies[k].initial_stress && !m.accepts_initial_stress())
      body_nodes[k].fail("initial_stress", "material type '" + m.type() +
                                               "' starts from its own stress (a DEM point from "
                                               "its packing's)");
  }
  read_boundary_conditions(root, c);
  read_rigid_bodies(root, c);
  read_output(root, c, problem.materials);
  return problem;
}

}  // namespace mpm_lig::mpm
