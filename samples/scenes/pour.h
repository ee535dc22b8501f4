#pragma once

// The pour helpers are the kit's (scenes/kit/pour.h); scenes that take only its speed guard
// include them from here.
#include "scenes/kit/pour.h"

namespace sandphys::scenes {

using kit::pourGuardSpeed;

}  // namespace sandphys::scenes
