// thalassa — everything an application needs: include this one header and link
// thalassa::thalassa (find_package(thalassa)).
#pragma once

#include "thalassa/engine.hpp"
#include "thalassa/planet.hpp"
#include "thalassa/validation.hpp"
#include "thalassa/version.hpp"
