#pragma once
#include "deploy/fleet/launcher.hpp"
