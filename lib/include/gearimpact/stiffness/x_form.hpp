// The x-form route: the energies (16)-(19) integrated over the tooth centre
// line, with every section found from the polar involute by root finding.
// It shares no formula with the tau-form and so checks it.
#pragma once

#include "gearimpact/geometry/tooth_profile.hpp"
#include "gearimpact/stiffness/model.hpp"

namespace gearimpact {

// The same quantities as tau_form_compliances, by the x-form.
Compliances x_form_compliances(const InvoluteTooth& tooth, double contact_x_m,
                               double youngs_modulus_pa, double face_width_m,
                               const StiffnessModel& model);

}  // namespace gearimpact
