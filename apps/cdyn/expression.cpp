// expression.cpp — muParser-backed fields f(x, y, z, t).
#include "expression.hpp"

#include <memory>
#include <muParser.h>
#include <numbers>
#include <regex>

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

// The parser reads its variables by address, so each field owns its parser and the
// four variables together.  muParser is not re-entrant: a field must not be
// evaluated from two threads at once.
struct Evaluator {
  mu::Parser parser;
  double x = 0.0, y = 0.0, z = 0.0, t = 0.0;
};

}  // namespace

Field parse_expression(const std::string& text, const std::string& key) {
  auto e = std::make_shared<Evaluator>();
  try {
    e->parser.DefineVar("x", &e->x);
    e->parser.DefineVar("y", &e->y);
    e->parser.DefineVar("z", &e->z);
    e->parser.DefineVar("t", &e->t);
    e->parser.DefineConst("pi", std::numbers::pi);
    e->parser.SetExpr(text);
    e->parser.Eval();  // compile now, so that errors surface at parse time
  } catch (const mu::Parser::exception_type& err) {
    throw InputError(key + ": bad expression '" + text + "': " + err.GetMsg());
  }
  // muParser can also fail while evaluating (a compiled expression whose stack
  // evaluation it refuses); that too is the text's fault, reported as bad input with
  // the key, never as a foreign exception type escaping to the caller.
  Field f = [e, text, key](const Point& p, double t) {
    e->x = p.x, e->y = p.y, e->z = p.z, e->t = t;
    try {
      return e->parser.Eval();
    } catch (const mu::Parser::exception_type& err) {
      throw InputError(key + ": bad expression '" + text + "': " + err.GetMsg());
    }
  };
  // muParser knows which variables the compiled expression reads
  const auto used = e->parser.GetUsedVar();
  if (!used.count("x") && !used.count("y") && !used.count("z")) f.uniform_in_space();
  return f;
}

bool depends_on_time(const std::string& text) {
  static const std::regex t_alone(R"((^|[^A-Za-z0-9_])t($|[^A-Za-z0-9_]))");
  return std::regex_search(text, t_alone);
}

}  // namespace cdyn
