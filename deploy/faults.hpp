#pragma once
#include "deploy/fleet/fault_analysis.hpp"
#include "deploy/fleet/fault_schedule.hpp"
