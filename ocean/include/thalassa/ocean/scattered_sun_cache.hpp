// thalassa — the reference's scattered sun, kept for the next render of the same view.
#pragma once

#include <memory>

namespace thalassa::ocean {

// The last lattice of the reference's scattered sun (shaders/ocean/reference_sun_scatter.comp)
// that a render drew with this cache: the per-pixel sums it scattered, with everything they
// depend on (the view and its first sample's offset, whose grid depth hid the cells; the time;
// the waves; the lattice's cells; the refinement and the kind of atomics asked for). A later
// render given the same cache draws those sums instead of scattering again when it asks for that
// lattice without measuring its convergence, and scatters (and replaces them) otherwise. Not
// with wakes or calm areas (their buffers are not part of the key): those always scatter.
//
// What it is for: a reference rendered term by term scatters the same lattice for each term
// with the sun (validate: the sun term, whose lattice converges, then frame 0 of the term
// `all`, which draws the lattice the sun term ended with). Keep one cache per reference (one
// sea); it holds one lattice (4 floats a pixel). Not thread-safe; used on the GL thread.
class ScatteredSunCache;

std::shared_ptr<ScatteredSunCache> make_scattered_sun_cache();

}  // namespace thalassa::ocean
