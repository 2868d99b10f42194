#pragma once
// Arithmetic expressions of plan files (muParser underneath): x, y, c1.. and sqrt, sin, cos, ^.

#include <memory>
#include <string>
#include <vector>

namespace swath::energy {

/// A compiled expression over named variables. Copyable; evaluation is not thread-safe.
class Expression {
 public:
  /// Compiles `text` with `variables` (e.g. {"x", "y", "c1"}). Throws base::InputError
  /// "`where`: unknown variable 'z'" or "`where`: <syntax problem>".
  Expression(const std::string& text, const std::vector<std::string>& variables,
             const std::string& where);
  Expression(const Expression& other);
  Expression& operator=(const Expression& other);
  ~Expression();

  /// Value at `values` (in the order of the variables given).
  double operator()(const std::vector<double>& values) const;
  const std::string& text() const { return text_; }

 private:
  struct Impl;
  std::string text_;
  std::vector<std::string> variables_;
  std::string where_;
  std::unique_ptr<Impl> impl_;
};

/// Evaluates a constant expression (no variables), e.g. "-3*10^3". Throws InputError naming
/// `where`.
double constant(const std::string& text, const std::string& where);

}  // namespace swath::energy
