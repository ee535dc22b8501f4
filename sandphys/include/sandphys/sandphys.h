#pragma once

/// The whole public API of sandphys.
#include "sandphys/body.h"
#include "sandphys/colliders.h"
#include "sandphys/contact_model.h"
#include "sandphys/error.h"
#include "sandphys/gpu_context.h"
#include "sandphys/ids.h"
#include "sandphys/math.h"
#include "sandphys/mesh.h"
#include "sandphys/readback.h"
#include "sandphys/recording.h"
#include "sandphys/settings.h"
#include "sandphys/sleep_model.h"
#include "sandphys/spawn.h"
#include "sandphys/step_report.h"
#include "sandphys/world.h"
