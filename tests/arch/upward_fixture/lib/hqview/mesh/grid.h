#pragma once
// Fixture: mesh includes render, a module above it. The check must fail here.
#include "hqview/core/value.h"
#include "hqview/render/scene.h"
