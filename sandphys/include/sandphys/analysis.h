#pragma once

/// The analysis tools of the validation experiments: curve fits and empirical distributions.
#include "sandphys/analysis/contacts.h"
#include "sandphys/analysis/distributions.h"
#include "sandphys/analysis/fits.h"
#include "sandphys/analysis/heap.h"
