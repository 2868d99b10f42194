// The only translation unit of swath::energy that sees muParser.
#include "swath/energy/expression.hpp"

#include <muParser.h>

#include <cmath>

#include "swath/base/input_error.hpp"

namespace swath::energy {

namespace {

// muParser's messages name the offending token; turn the common one into plain words.
std::string explain(const mu::Parser::exception_type& e) {
  if (e.GetCode() == mu::ecUNASSIGNABLE_TOKEN || e.GetCode() == mu::ecUNEXPECTED_VAR)
    return "unknown variable '" + e.GetToken() + "'";
  return e.GetMsg();
}

}  // namespace

struct Expression::Impl {
  mu::Parser parser;
  std::vector<double> values;

  void compile(const std::string& text, const std::vector<std::string>& variables,
               const std::string& where) {
    values.assign(variables.size(), 0.0);
    try {
      for (std::size_t i = 0; i < variables.size(); ++i) parser.DefineVar(variables[i], &values[i]);
      parser.SetExpr(text);
      parser.Eval();  // parses now: unknown names and syntax errors surface here
    } catch (const mu::Parser::exception_type& e) {
      throw base::InputError(where + ": " + explain(e) + " in '" + text + "'");
    }
  }
};

Expression::Expression(const std::string& text, const std::vector<std::string>& variables,
                       const std::string& where)
    : text_(text), variables_(variables), where_(where), impl_(std::make_unique<Impl>()) {
  impl_->compile(text_, variables_, where_);
}

Expression::Expression(const Expression& o)
    : text_(o.text_), variables_(o.variables_), where_(o.where_), impl_(std::make_unique<Impl>()) {
  impl_->compile(text_, variables_, where_);  // muParser binds variables by address: rebind
}

Expression& Expression::operator=(const Expression& o) {
  if (this != &o) {
    Expression copy(o);
    std::swap(text_, copy.text_);
    std::swap(variables_, copy.variables_);
    std::swap(where_, copy.where_);
    std::swap(impl_, copy.impl_);
  }
  return *this;
}

Expression::~Expression() = default;

double Expression::operator()(const std::vector<double>& values) const {
  for (std::size_t i = 0; i < impl_->values.size() && i < values.size(); ++i)
    impl_->values[i] = values[i];
  return impl_->parser.Eval();
}

double constant(const std::string& text, const std::string& where) {
  const double v = Expression(text, {}, where)({});
  if (!std::isfinite(v)) throw base::InputError(where + ": '" + text + "' is not a finite number");
  return v;
}

}  // namespace swath::energy
