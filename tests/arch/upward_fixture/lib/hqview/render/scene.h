#pragma once
// Fixture: render includes mesh, which is allowed.
#include "hqview/mesh/grid.h"
