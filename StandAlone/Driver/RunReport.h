// report.html: one self-contained page (inline SVG plots, pictures as data URIs; no script, no
// server) that says what a run did, from the files of its output directory alone (history.csv,
// input.ups, images/*.png): lithium and state of charge, dt and the rule that set it, the
// quasi-static check (kinetic over elastic energy), the ranges of c and J, Newton and Krylov
// iterations of implicit runs, and the run's pictures. sus writes it at each checkpoint and at the
// end; `render_vtu --report DIR` writes it again (docs/output.md, "report.html").
#pragma once

#include <string>

namespace anode {

// The quasi-static check's bound on kinetic / elastic energy. Below it the stress that
// accelerates the material is under sqrt(1e-2) = 10% of the stress: an elastic vibration's
// stress energy equals its kinetic energy, and slower motion carries less stress per kinetic
// energy, so sqrt(KE/E_el) bounds the dynamic part of the stress (docs/output.md). Above it the
// check cannot vouch for a quasi-static answer (a raised density may still give one).
constexpr double kQuasiStaticEnergyRatio = 1e-2;

// Writes DIR/report.html (atomically) and returns its path. `status` is a sentence about the
// run's state ("Written at the end of the run.").
std::string writeRunReport(const std::string& dir, const std::string& status);

}  // namespace anode
