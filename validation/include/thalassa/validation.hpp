// thalassa — the validation module's public surface (issue 6): error metrics of a rendering
// method against a reference image, suite files, and the report of `thalassa validate`.
#pragma once

#include "thalassa/validation/metrics.hpp"
#include "thalassa/validation/report.hpp"
#include "thalassa/validation/runner.hpp"
#include "thalassa/validation/suite.hpp"
