#include "planning/ground_mission/ground_mission_planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <ostream>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <string>

#include "control/constants.h"
#include "control/require.h"
#include "planning/ground_mission/place_search.h"

namespace aperture::planning {
namespace {

using control::kDegToRad;
using control::kInf;

// The largest ratio of an 8-connected grid path's octile length to the Euclidean length of the
// straight line it follows, sqrt(1 + (sqrt 2 - 1)^2) = sqrt(4 - 2 sqrt 2) = 1.08239 (at 22.5
// deg), rounded up so the bound stays below the true cost.
constexpr double kOctilePerEuclidean = 1.0824;

std::string Describe(const Eigen::Vector2d& p_W) {
  std::ostringstream out;
  out << "(" << p_W.x() << ", " << p_W.y() << ") m";
  return out.str();
}

void ValidateScene(const GroundMissionScene& scene, const GroundMissionParams& params) {
  const auto inside = [&](const Eigen::Vector2d& p_W) {
    return (p_W.array() >= scene.area_min_W.array()).all() &&
           (p_W.array() <= scene.area_max_W.array()).all();
  };
  if (!inside(scene.robot_p_W)) {
    throw std::invalid_argument("ground mission scene: the robot at " + Describe(scene.robot_p_W) +
                                " lies outside the field; move it into the area");
  }
  if (!inside(scene.goal_p_W)) {
    throw std::invalid_argument("ground mission scene: the goal at " + Describe(scene.goal_p_W) +
                                " lies outside the field; move it into the area");
  }
  if (!(scene.goal_radius_m >= 0.0) ||
      !(params.grasp_radius_m > params.robot_radius_m + scene.goal_radius_m)) {
    throw std::invalid_argument(
        "ground mission scene: goal_radius_m = " + std::to_string(scene.goal_radius_m) +
        " must be >= 0 and below grasp_radius_m - robot_radius_m, or the robot cannot reach the "
        "goal to deliver the kit");
  }
  for (size_t k = 0; k < scene.movable_obstacles.size(); ++k) {
    const double radius_m = CircumscribedRadius(scene.movable_obstacles[k]);
    if (!(params.grasp_radius_m > params.robot_radius_m + radius_m)) {
      throw std::invalid_argument("ground mission scene: movable obstacle " + std::to_string(k) +
                                  " (circumscribed radius " + std::to_string(radius_m) +
                                  " m) hides its own grasp circle; grasp_radius_m must exceed "
                                  "robot_radius_m + that radius");
    }
  }
}

void ValidateParams(const GroundMissionParams& params) {
  control::RequirePositive(params.cell_size_m, "GroundMissionParams.cell_size_m");
  control::RequirePositive(params.robot_radius_m, "GroundMissionParams.robot_radius_m");
  control::RequirePositive(params.grasp_radius_m, "GroundMissionParams.grasp_radius_m");
  control::RequirePositive(params.driving_speed_mps, "GroundMissionParams.driving_speed_mps");
  control::RequirePositive(params.turn_rate_deg_s, "GroundMissionParams.turn_rate_deg_s");
  control::RequireNonNegative(params.remove_time_s, "GroundMissionParams.remove_time_s");
}

// The map without movable obstacles, after checking the parameters and the scene.
OccupancyGrid BuildFixedGrid(const GroundMissionScene& scene, const GroundMissionParams& params) {
  ValidateParams(params);
  ValidateScene(scene, params);
  OccupancyGrid grid(scene.area_min_W, scene.area_max_W, params.cell_size_m);
  grid.BlockBorder(params.robot_radius_m);
  for (const GroundBox& box : scene.fixed_obstacles) grid.BlockBox(box, params.robot_radius_m);
  grid.BlockDisc(scene.goal_p_W, scene.goal_radius_m, params.robot_radius_m);
  return grid;
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

std::vector<int> GroundMission::Order() const {
  std::vector<int> order;
  for (const GroundObstacleRemoval& removal : removals) order.push_back(removal.obstacle);
  return order;
}

double GroundMission::path_length_m() const {
  double length_m = 0.0;
  for (const GroundMissionLeg& leg : legs) length_m += leg.length_m;
  return length_m;
}

std::ostream& operator<<(std::ostream& out, const GroundMission& mission) {
  if (!mission.solved()) {
    return out << "no mission (" << mission.missions_expanded << " partial missions expanded in "
               << mission.solve_time_s << " s)";
  }
  out << "mission " << mission.cost_s << " s (drive " << mission.drive_s << " s, turn "
      << mission.turn_s << " s, remove " << mission.remove_s << " s, backward "
      << mission.backward_s << " s), path " << mission.path_length_m() << " m, removals [";
  for (size_t i = 0; i < mission.removals.size(); ++i) {
    const GroundObstacleRemoval& removal = mission.removals[i];
    out << (i ? ", " : "") << removal.obstacle << " -> " << Describe(removal.place_p_W);
    if (removal.backward_m > 0.0) out << " (" << removal.backward_m << " m back)";
  }
  return out << "], " << mission.missions_expanded << " expanded in " << mission.solve_time_s
             << " s";
}

GroundMissionPath BuildMissionPath(const std::vector<GroundMissionLeg>& legs) {
  GroundMissionPath path;
  for (const GroundMissionLeg& leg : legs) {
    for (const GroundWaypoint& waypoint : leg.waypoints) path.polyline.Append(waypoint.p_W);
    path.leg_end_s_m.push_back(path.polyline.length_m());
  }
  return path;
}

GroundMissionPlanner::GroundMissionPlanner(const GroundMissionScene& scene,
                                           const GroundMissionParams& params)
    : scene_(scene), params_(params), fixed_grid_(BuildFixedGrid(scene, params)) {
  const std::optional<int> start = fixed_grid_.CellAt(scene.robot_p_W);
  bool start_free = start && !fixed_grid_.blocked(*start);
  for (const GroundBox& box : scene.movable_obstacles) {
    start_free = start_free && (scene.robot_p_W - box.p_W).norm() >
                                   CircumscribedRadius(box) + params.robot_radius_m;
  }
  if (!start_free) {
    throw std::invalid_argument("ground mission scene: the robot at " + Describe(scene.robot_p_W) +
                                " collides with an obstacle or the border (robot radius " +
                                std::to_string(params.robot_radius_m) +
                                " m); move the robot or the obstacle");
  }
  const std::vector<int> deliveries =
      fixed_grid_.FreeCellsWithin(scene.goal_p_W, params.grasp_radius_m);
  goal_distance_fixed_m_ = RunGridDijkstra(fixed_grid_, deliveries).distance_m;
}

OccupancyGrid GroundMissionPlanner::MapWithout(const std::vector<int>& removed) const {
  OccupancyGrid map = fixed_grid_;
  for (size_t k = 0; k < scene_.movable_obstacles.size(); ++k) {
    if (std::find(removed.begin(), removed.end(), static_cast<int>(k)) != removed.end()) continue;
    const GroundBox& box = scene_.movable_obstacles[k];
    map.BlockDisc(box.p_W, CircumscribedRadius(box), params_.robot_radius_m);
  }
  return map;
}

std::optional<GroundMissionLeg> GroundMissionPlanner::MakeLeg(const OccupancyGrid& map,
                                                              const GridDistances& distances,
                                                              const Stop& from, int target) const {
  const Eigen::Vector2d target_W =
      target < 0 ? scene_.goal_p_W : scene_.movable_obstacles[static_cast<size_t>(target)].p_W;
  const int end =
      NearestReachableCell(distances, map.FreeCellsWithin(target_W, params_.grasp_radius_m));
  if (end < 0) return std::nullopt;
  const std::vector<int> cells = RefineGridPath(map, ExtractGridPath(distances, end));
  const Eigen::Vector2d to_target_W = target_W - map.CenterOf(end);
  GroundMissionLeg leg;
  leg.target = target;
  leg.waypoints = OrientWaypoints(map, cells, std::atan2(to_target_W.y(), to_target_W.x()));
  double yaw_rad = from.yaw_rad;
  for (size_t i = 0; i < leg.waypoints.size(); ++i) {
    if (i > 0) leg.length_m += (leg.waypoints[i].p_W - leg.waypoints[i - 1].p_W).norm();
    leg.turn_rad +=
        std::abs(std::remainder(leg.waypoints[i].yaw_rad - yaw_rad, 2.0 * control::kPi));
    yaw_rad = leg.waypoints[i].yaw_rad;
  }
  leg.time_s = leg.length_m / params_.driving_speed_mps +
               leg.turn_rad / (params_.turn_rate_deg_s * kDegToRad);
  return leg;
}

GroundMissionPlanner::Expansion GroundMissionPlanner::Expand(const Partial& partial) const {
  // Alg. 2 "add remaining obstacles to map", then one single-source Dijkstra from the stop.
  const OccupancyGrid map = MapWithout(partial.order);
  const GridDistances distances = RunGridDijkstra(map, {partial.stop.cell});
  Expansion expansion;
  expansion.to_obstacle.resize(scene_.movable_obstacles.size());
  for (size_t k = 0; k < scene_.movable_obstacles.size(); ++k) {
    const int obstacle = static_cast<int>(k);
    if (std::find(partial.order.begin(), partial.order.end(), obstacle) != partial.order.end()) {
      continue;
    }
    expansion.to_obstacle[k] = MakeLeg(map, distances, partial.stop, obstacle);
  }
  expansion.to_goal = MakeLeg(map, distances, partial.stop, -1);
  return expansion;
}

double GroundMissionPlanner::LowerBoundToGoal_s(int cell) const {
  return goal_distance_fixed_m_[static_cast<size_t>(cell)] /
         (kOctilePerEuclidean * params_.driving_speed_mps);
}

GroundMissionPlanner::Partial GroundMissionPlanner::Start() const {
  Partial start;
  start.stop = {*fixed_grid_.CellAt(scene_.robot_p_W), scene_.robot_yaw_rad};
  start.bound_s = LowerBoundToGoal_s(start.stop.cell);
  return start;
}

GroundMissionPlanner::Partial GroundMissionPlanner::Extend(const Partial& partial,
                                                           const GroundMissionLeg& leg) const {
  Partial next = partial;
  next.order.push_back(leg.target);
  next.legs.push_back(leg);
  const Eigen::Vector2d end_W = leg.waypoints.back().p_W;
  next.stop = {*fixed_grid_.CellAt(end_W), leg.waypoints.back().yaw_rad};
  next.cost_s = partial.cost_s + leg.time_s + params_.remove_time_s;
  next.bound_s = next.cost_s + LowerBoundToGoal_s(next.stop.cell);
  return next;
}

GroundMission GroundMissionPlanner::Complete(const Partial& partial,
                                             const GroundMissionLeg& to_goal) const {
  GroundMission mission;
  mission.legs = partial.legs;
  mission.legs.push_back(to_goal);
  const GroundMissionPath mission_path = BuildMissionPath(mission.legs);
  const GroundPolyline& path = mission_path.polyline;
  const std::vector<double>& stop_s_m = mission_path.leg_end_s_m;
  for (const GroundMissionLeg& leg : mission.legs) {
    mission.drive_s += leg.length_m / params_.driving_speed_mps;
    mission.turn_s += leg.turn_rad / (params_.turn_rate_deg_s * kDegToRad);
  }
  PlaceSearchContext context;
  context.scene = &scene_;
  context.path = &path;
  context.robot_radius_m = params_.robot_radius_m;
  context.lateral_m = params_.grasp_radius_m;
  context.step_m = params_.cell_size_m;
  for (size_t i = 0; i < partial.order.size(); ++i) {
    const int obstacle = partial.order[i];
    context.in_place.clear();
    for (size_t k = 0; k < scene_.movable_obstacles.size(); ++k) {
      const auto removed_end = partial.order.begin() + static_cast<std::ptrdiff_t>(i) + 1;
      if (std::find(partial.order.begin(), removed_end, static_cast<int>(k)) != removed_end) {
        continue;
      }
      const GroundBox& box = scene_.movable_obstacles[k];
      context.in_place.push_back({box.p_W, CircumscribedRadius(box)});
    }
    const double radius_m =
        CircumscribedRadius(scene_.movable_obstacles[static_cast<size_t>(obstacle)]);
    const std::optional<PlaceLocation> place =
        FindPlaceLocation(context, radius_m, stop_s_m[i], stop_s_m[i + 1]);
    if (!place) {
      mission.status = GroundMissionStatus::kNoMission;
      mission.cost_s = kInf;
      return mission;
    }
    GroundObstacleRemoval removal;
    removal.obstacle = obstacle;
    removal.grasp_p_W = path.PointAt(stop_s_m[i]);
    removal.place_p_W = place->p_W;
    removal.robot_at_place_p_W = path.PointAt(place->robot_s_m);
    removal.grasp_s_m = stop_s_m[i];
    removal.place_s_m = place->robot_s_m;
    removal.backward_m = std::max(0.0, stop_s_m[i] - place->robot_s_m);
    mission.removals.push_back(removal);
    context.placed.push_back({place->p_W, radius_m});
    mission.remove_s += params_.remove_time_s;
    mission.backward_s += 2.0 * removal.backward_m / params_.driving_speed_mps;
  }
  mission.status = GroundMissionStatus::kSolved;
  mission.cost_s = partial.cost_s + to_goal.time_s + mission.backward_s;
  return mission;
}

GroundMission GroundMissionPlanner::Plan() const {
  const auto started = std::chrono::steady_clock::now();
  // Least bound first; on equal bounds the earlier pushed (std::priority_queue is a max-heap).
  struct Queued {
    Partial partial;
    long sequence;
  };
  const auto later = [](const Queued& a, const Queued& b) {
    if (a.partial.bound_s != b.partial.bound_s) return a.partial.bound_s > b.partial.bound_s;
    return a.sequence > b.sequence;
  };
  std::priority_queue<Queued, std::vector<Queued>, decltype(later)> queue(later);
  long pushed = 0;
  queue.push({Start(), pushed++});
  GroundMission best;
  int expanded = 0;
  while (!queue.empty() && queue.top().partial.bound_s < best.cost_s) {
    const Partial current = queue.top().partial;
    queue.pop();
    ++expanded;
    const Expansion expansion = Expand(current);
    for (const auto& leg : expansion.to_obstacle) {
      if (!leg) continue;
      Partial next = Extend(current, *leg);
      if (next.bound_s < best.cost_s) queue.push({std::move(next), pushed++});
    }
    if (expansion.to_goal) {
      GroundMission mission = Complete(current, *expansion.to_goal);
      if (mission.cost_s < best.cost_s) best = std::move(mission);
    }
  }
  best.missions_expanded = expanded;
  best.solve_time_s = Seconds(started);
  return best;
}

GroundMission GroundMissionPlanner::PlanExhaustively() const {
  const auto started = std::chrono::steady_clock::now();
  GroundMission best;
  int visited = 0;
  // Depth first over the orders, obstacles in index order, so the first of equal costs is the
  // lowest order lexicographically (shorter orders first where one is a prefix).
  std::function<void(const Partial&)> visit = [&](const Partial& partial) {
    ++visited;
    const Expansion expansion = Expand(partial);
    if (expansion.to_goal) {
      GroundMission mission = Complete(partial, *expansion.to_goal);
      if (mission.cost_s < best.cost_s) best = std::move(mission);
    }
    for (const auto& leg : expansion.to_obstacle) {
      if (leg) visit(Extend(partial, *leg));
    }
  };
  visit(Start());
  best.missions_expanded = visited;
  best.solve_time_s = Seconds(started);
  return best;
}

GroundMission GroundMissionPlanner::EvaluateOrder(const std::vector<int>& order) const {
  const auto started = std::chrono::steady_clock::now();
  Partial partial = Start();
  GroundMission mission;
  for (const int obstacle : order) {
    if (obstacle < 0 || obstacle >= static_cast<int>(scene_.movable_obstacles.size()) ||
        std::find(partial.order.begin(), partial.order.end(), obstacle) != partial.order.end()) {
      throw std::invalid_argument("GroundMissionPlanner::EvaluateOrder: obstacle " +
                                  std::to_string(obstacle) +
                                  " is not a movable obstacle of the scene or is repeated");
    }
    const std::optional<GroundMissionLeg> leg =
        Expand(partial).to_obstacle[static_cast<size_t>(obstacle)];
    ++mission.missions_expanded;
    if (!leg) {
      mission.solve_time_s = Seconds(started);
      return mission;
    }
    partial = Extend(partial, *leg);
  }
  const Expansion expansion = Expand(partial);
  const int expanded = mission.missions_expanded + 1;
  if (expansion.to_goal) mission = Complete(partial, *expansion.to_goal);
  mission.missions_expanded = expanded;
  mission.solve_time_s = Seconds(started);
  return mission;
}

}  // namespace aperture::planning
