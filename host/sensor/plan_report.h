#pragma once
// A sensor plan as text: the table `flexsight sensor-plan` prints, report.md (the same
// figures as Markdown tables) and report.json (every figure under stable keys).
#include <string>

#include "host/sensor/sensor_plan.h"

namespace flexsight {

std::string plan_table(const SensorPlan& plan);
std::string plan_markdown(const SensorPlan& plan);
std::string plan_json(const SensorPlan& plan);

}  // namespace flexsight
