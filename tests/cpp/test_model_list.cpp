// The model list (models/model_list.hpp) and the compensator list
// (compensators/compensator_list.hpp): what follows from them (ModelPart's members, ForwardModel's
// variant, the inverse's and the loader's dispatch, the closed loop of each compensator).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <tendonsheath/tendonsheath.hpp>
#include <type_traits>
#include <variant>

namespace ts = tendonsheath;

namespace {

// whether T is one of variant V's alternatives
template <class T, class V>
struct is_alternative;
template <class T, class... Ts>
struct is_alternative<T, std::variant<Ts...>> : std::disjunction<std::is_same<T, Ts>...> {};
template <class T>
constexpr bool runs_first = is_alternative<T, ts::ForwardModel::First>::value;

// the index of T among variant V's alternatives (its size when T is none)
template <class T, class V>
struct index_in;
template <class T, class... Ts>
struct index_in<T, std::variant<Ts...>> {
  static constexpr std::size_t value = [] {
    std::size_t i = 0;
    (void)((std::is_same_v<T, Ts> ? false : (++i, true)) && ...);
    return i;
  }();
};

}  // namespace

// (a model added to the list is covered by the TEST below, with no edit here)
static_assert(runs_first<ts::Backlash> && runs_first<ts::BoucWenBacklash> &&
                  runs_first<ts::BoucWen> && runs_first<ts::PrandtlIshlinskii> &&
                  runs_first<ts::GeneralizedPrandtlIshlinskii> && runs_first<ts::Polynomial> &&
                  runs_first<ts::PlantModel>,
              "ForwardModel runs the root-invertible models of the list");
static_assert(!runs_first<ts::HystereticOscillator> && !runs_first<ts::CurveAngleModel>,
              "the models with an inverse of their own are not root-searched");

static_assert(ts::angle_dependent_base<ts::Backlash> && ts::angle_dependent_base<ts::BoucWen> &&
                  ts::angle_dependent_base<ts::BoucWenBacklash> &&
                  ts::angle_dependent_base<ts::HystereticOscillator>,
              "the models with an AngleDependent engine");
static_assert(!ts::angle_dependent_base<ts::PrandtlIshlinskii> &&
                  !ts::angle_dependent_base<ts::PlantModel> &&
                  !ts::angle_dependent_base<ts::CurveAngleModel>,
              "no AngleDependent engine of their own");

TEST(ModelList, EachModelHasItsOwnPartMemberAndKind) {
  std::set<std::string> kinds, members;
  std::set<const void*> addresses;
  ts::ModelPart part;
  ts::for_each_type(ts::Models{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    kinds.insert(ts::model_kind<M>());
    members.insert(ts::PartMember<M>::name);
    addresses.insert(&ts::part_params<M>(part));
    bool found = false;
    EXPECT_TRUE(ts::visit_model_kind(ts::model_kind<M>(), [&](auto t) {
      found = std::is_same_v<typename decltype(t)::type, M>;
    }));
    EXPECT_TRUE(found) << ts::model_kind<M>();
  });
  EXPECT_EQ(kinds.size(), ts::Models::size);
  EXPECT_EQ(members.size(), ts::Models::size);
  EXPECT_EQ(addresses.size(), ts::Models::size);
  EXPECT_EQ(kinds.count("BoucWenBacklash"), 1u);
  EXPECT_EQ(members.count("bouc_wen_backlash"), 1u);
  EXPECT_FALSE(ts::visit_model_kind("FirstOrderLag", [](auto) {}));
  EXPECT_FALSE(ts::visit_model_kind("AngleDependent", [](auto) {}));
}

TEST(ModelList, ForwardModelRunsExactlyTheRootInvertibleModelsInTheListsOrder) {
  std::size_t alternatives = 0;
  ts::for_each_type(ts::Models{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    static_assert(runs_first<M> == ts::root_invertible<M>::value);
    if constexpr (ts::root_invertible<M>::value) {
      EXPECT_EQ((index_in<M, ts::ForwardModel::First>::value), alternatives)  // the list's order
          << ts::model_kind<M>();
      ++alternatives;
    }
  });
  EXPECT_EQ(alternatives, std::variant_size_v<ts::ForwardModel::First>);
}

TEST(ModelList, EveryRootInvertibleModelGetsARootInverseFromItsPart) {
  // a model of the list without an inverse of its own is inverted by the root search on it
  ts::InverseModel m;
  m.parts.resize(1);
  m.parts[0].kind = "BoucWen";
  m.parts[0].bouc_wen.A = 1.0;
  ts::InverseSettings s;
  s.range = ts::InputRange{-2.0, 2.0};
  ts::ModelInverse inv = ts::make_model_inverse(m, s);
  EXPECT_TRUE(std::holds_alternative<ts::RootInverse<ts::ForwardModel>>(inv.core()));
  ts::BoucWen forward(m.parts[0].bouc_wen);
  double worst = 0.0;
  for (int k = 0; k < 400; ++k) {
    const double y_d = 0.5 * std::sin(0.03 * k);
    const double u = inv.step(y_d, 1e-3);
    worst = std::max(worst, std::fabs(forward.step(u, 1e-3) - y_d));
  }
  EXPECT_LT(worst, 1e-6);  // the root search's tolerance is far below this
}

namespace {

// Steps loops a and b with the same random signals (dropouts, route changes included) and
// expects the same commands, statuses and fallbacks, bit for bit.
template <class A, class B>
void expect_same_loop(A a, B b, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  a.reset();
  b.reset();
  for (int k = 0; k < 2000; ++k) {
    if (k % 250 == 0) {
      const double theta = 1.0 + u(rng);
      const ts::ShapeIntegrals s{1.0 + 0.1 * u(rng), 1.0 + 0.1 * u(rng), theta};
      a.on_shape(s);
      b.on_shape(s);
    }
    const double y_d = 0.5 * std::sin(0.01 * k), motor = y_d + 0.01 * u(rng);
    const double measured = (k / 100) % 5 == 3 ? NAN : y_d + 0.02 * u(rng);
    const double dt = k == 0 ? 0.0 : 1e-3;
    ASSERT_EQ(a.command(y_d, measured, motor, dt), b.command(y_d, measured, motor, dt)) << k;
    ASSERT_EQ(a.status(), b.status()) << k;
    ASSERT_EQ(a.in_fallback(), b.in_fallback()) << k;
  }
}

template <class C>
void expect_generic_loop_matches(const C& c, unsigned seed) {
  expect_same_loop(ts::loop_of_t<C>{c}, ts::CompensatorLoop<C>{c}, seed);
}

ts::ModelInverse curve_angle_model_inverse() {
  ts::InverseModel m;
  m.parts.resize(1);
  m.parts[0].kind = "CurveAngleModel";
  return ts::make_model_inverse(m, ts::InverseSettings{});
}

}  // namespace

TEST(CompensatorList, TheGenericLoopRunsEachCompensatorAsItsNamedLoop) {
  // what a compensator added to Compensators without a LoopOf of its own gets: the same loop
  expect_generic_loop_matches(curve_angle_model_inverse(), 1);
  expect_generic_loop_matches(ts::CurveAngleFeedforward(ts::CurveAngleFeedforwardParams{}), 2);
  expect_generic_loop_matches(ts::AdaptiveController(ts::AdaptiveControllerParams{}), 3);
  expect_generic_loop_matches(ts::ContinuumFeedforward(ts::ContinuumFeedforwardParams{}), 4);
  ts::BacklashInverseParams b;
  b.B_r = b.B_l = 0.05;
  expect_generic_loop_matches(ts::BacklashInverseFeedforward(b), 5);
  ts::PrandtlIshlinskiiParams pi{{0.0, 0.1, 0.2}, {1.0, 0.3, 0.2}};
  expect_generic_loop_matches(ts::PrandtlIshlinskiiFeedforward(pi, ts::CommandLimits{}), 6);
}

TEST(CompensatorList, EveryCompensatorOfTheListHasALoop) {
  std::size_t n = 0;
  ts::for_each_type(ts::Compensators{}, [&](auto tag) {
    using C = typename decltype(tag)::type;
    using L = ts::loop_of_t<C>;
    static_assert(noexcept(std::declval<L&>().command(0.0, 0.0, 0.0, 0.0)));
    static_assert(noexcept(std::declval<L&>().reset()));
    ++n;
  });
  EXPECT_EQ(n, ts::Compensators::size);
}
