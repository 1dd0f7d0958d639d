#include "experiments/missions/mission_registry.h"

#include <sstream>
#include <stdexcept>
#include <utility>

#include "config/usage_error.h"

namespace aperture::experiments {

void MissionRegistry::Register(const std::string& name, std::string description,
                               std::vector<std::string> scenarios, MissionFactory factory) {
  if (name.empty()) throw std::invalid_argument("MissionRegistry: empty mission name");
  if (!factory) {
    throw std::invalid_argument("MissionRegistry: mission '" + name + "' has no factory");
  }
  if (entries_.count(name)) {
    throw std::invalid_argument("MissionRegistry: mission '" + name + "' is registered twice");
  }
  for (const std::string& scenario : scenarios) {
    const auto [it, inserted] = default_for_scenario_.emplace(scenario, name);
    if (!inserted) {
      throw std::invalid_argument("MissionRegistry: scenario '" + scenario +
                                  "' already flies mission '" + it->second + "' by default");
    }
  }
  entries_.emplace(name, Entry{std::move(description), std::move(factory)});
}

std::vector<std::string> MissionRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& [name, entry] : entries_) names.push_back(name);
  return names;
}

const MissionRegistry::Entry& MissionRegistry::Find(const std::string& name) const {
  const auto it = entries_.find(name);
  if (it != entries_.end()) return it->second;
  std::ostringstream message;
  message << "unknown mission '" << name << "'; known missions:";
  for (const auto& [known, entry] : entries_) message << " " << known;
  throw config::UsageError(message.str());  // the name came from --mission or --set mission=
}

const std::string& MissionRegistry::Description(const std::string& name) const {
  return Find(name).description;
}

const std::string& MissionRegistry::DefaultFor(const std::string& scenario) const {
  const auto it = default_for_scenario_.find(scenario);
  if (it != default_for_scenario_.end()) return it->second;
  std::ostringstream message;
  message << "no mission flies scenario '" << scenario << "' by default; name one with "
          << "--mission (known missions:";
  for (const auto& [known, entry] : entries_) message << " " << known;
  message << ")";
  throw std::invalid_argument(message.str());
}

std::unique_ptr<MissionFlight> MissionRegistry::Create(const std::string& name,
                                                       const MissionContext& context) const {
  std::unique_ptr<MissionFlight> flight = Find(name).factory(context);
  if (!flight) {
    throw std::invalid_argument("MissionRegistry: the factory of '" + name + "' returned nothing");
  }
  context.params.RejectUnknownKeys();
  return flight;
}

sim::SitlHooks MakeMissionHooks(MissionFlight* flight, sim::Scenario* scenario) {
  sim::SitlHooks hooks = sim::MakeScenarioHooks(scenario);
  hooks.before_render = [flight, scenario, attach_to_body = hooks.before_render](
                            double t_s, const control::QuadState& state) {
    flight->MoveObjects(t_s, &scenario->scene());
    attach_to_body(t_s, state);
  };
  return hooks;
}

}  // namespace aperture::experiments
