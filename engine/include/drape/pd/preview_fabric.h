#pragma once
// The fabric the preview simulates: each fabric's stretch (and shear) stiffness capped by a Courant-type limit on the
// preview's time step, so that an in-plane elastic wave crosses at most a few mesh edges per step.
//
// The preview assembles the garment quasi-statically: its stitches close the seams within a step or two. When the
// fabric's stiffness outweighs the mass term M / h^2 by far, one solve carries the panels' whole elastic response,
// and the seams close straight through the body where vertex contacts cannot steer them. The default t-shirt tore
// its sleeves this way in every fabric preset but jersey (Courant number 18-26 at 1/480 s against jersey's 4.7;
// docs/BENCHMARKS.md, "Findings worth keeping"). The Newton drape keeps the fabric's own stiffness.
#include "drape/model/cloth_model.h"

namespace drape::pd {

// sqrt(k / rho) h / mean rest edge length, with k the larger of a fabric's warp and weft stretch stiffness (N/m)
// and rho its areal density (kg/m^2), for the model's fastest fabric (0 without triangles or mass).
double courantNumber(const model::ClothModel& model, double h);

// The model with every triangle whose fabric has a Courant number above `limit` at step h made softer in stretch
// and shear by the same factor (so its anisotropy stays), to exactly `limit`; bending, density and everything else
// unchanged. limit <= 0: the model as it is.
model::ClothModel previewFabricModel(const model::ClothModel& model, double h, double limit);

}  // namespace drape::pd
