// The terms of a pair's compliance, as an open set: each term has one entry in
// kTerms, and every container of compliances is an array over the terms, so a
// new term is its integrand, its entry here and its case in the routes
// (tau_form.cpp, x_form.cpp, and mesh_models.cpp for the models beyond the
// paper). docs/model.md, section Stiffness; docs/stiffness-models.md, section 2.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

namespace gearimpact {

enum class Term { hertz, bending, axial, shear, foundation };
inline constexpr std::size_t kTermCount = 5;

struct TermInfo {
  Term term;
  // "bending": names the term in case files (the [model] key bending_term
  // switches it) and in outputs (bending_energy_max_J).
  std::string_view id;
  std::string_view switch_key;   // the [model] key that switches it: "bending_term"
  std::string_view description;  // for messages and documents
  // Column of its stiffness in tables: per tooth with the gear's number
  // appended (kb1, kb2), else as is (kh).
  std::string_view column;
  // false: one value for the pair (the Hertzian contact, (4)), constant along
  // the line of action; true: one per tooth, a function of the contact position.
  bool per_tooth;
};

// In the order in which (29) sums them; the terms beyond the paper's come
// last, so that for the paper's model (where they are 0) the sum is the
// paper's to the bit.
inline constexpr std::array<TermInfo, kTermCount> kTerms{{
    {Term::hertz, "hertz", "hertz_term", "the Hertzian term 1/Kh of (4)", "kh", false},
    {Term::bending, "bending", "bending_term", "the bending terms 1/Kb1 + 1/Kb2, (20),(22),(23)",
     "kb", true},
    {Term::axial, "axial", "axial_term", "the axial terms 1/Ka1 + 1/Ka2, (21),(24)", "ka", true},
    {Term::shear, "shear", "shear_term", "the shear terms 1/Ks1 + 1/Ks2 (Tian 2004)", "ks", true},
    {Term::foundation, "foundation", "foundation_term",
     "the fillet-foundation terms 1/Kf1 + 1/Kf2 (Sainsot et al. 2004)", "kf", true},
}};

constexpr std::size_t index_of(Term term) {
  return static_cast<std::size_t>(term);
}
constexpr const TermInfo& info(Term term) {
  return kTerms[index_of(term)];
}

// Which terms enter the mesh compliance. All by default; switching one off
// shows what it contributes (the paper's section 8 compares them).
struct TermSet {
  std::array<bool, kTermCount> on{true, true, true, true, true};
  bool has(Term term) const { return on[index_of(term)]; }
  void set(Term term, bool value) { on[index_of(term)] = value; }
  bool any() const {
    for (bool b : on) {
      if (b) return true;
    }
    return false;
  }
};
inline bool operator==(const TermSet& a, const TermSet& b) {
  return a.on == b.on;
}

// Compliances by term, m/N. For one tooth (a per-pair term is 0 there), or for
// a pair as it enters (29): per-tooth terms summed over both teeth.
struct Compliances {
  std::array<double, kTermCount> m_per_n{};
  double of(Term term) const { return m_per_n[index_of(term)]; }
  double& of(Term term) { return m_per_n[index_of(term)]; }
  // The series sum of (29), in the order of kTerms.
  double total_m_per_n() const {
    double sum = 0.0;
    for (double c : m_per_n) sum += c;
    return sum;
  }
};

// The terms a set switches on, the others 0: what enters (29).
inline Compliances included(const Compliances& all, const TermSet& terms) {
  Compliances result;
  for (const TermInfo& t : kTerms) {
    result.of(t.term) = terms.has(t.term) ? all.of(t.term) : 0.0;
  }
  return result;
}

}  // namespace gearimpact
