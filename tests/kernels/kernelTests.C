/*---------------------------------------------------------------------------*\
Description
    Unit tests of the SPH kernels (paper eqs. 11-14): each of WendlandC2,
    cubicSpline and quinticSpline, for smoothing lengths h of 0.01, 1 and 3,
    is normalised in 2D, vanishes outside its support, has the gradient
    factor F = (dW/dr)/r of its W, whose lattice first moment
    sum_j (x_j - x_i) (x) grad_i W_ij V_j is the identity (equivalently
    sum_j y y^T F V_j = -I with y = x_j - x_i), and is positive and
    decreasing; the run-time selection reads `kernel` with its default and
    rejects unknown names; visit() hands over the selected struct.

\*---------------------------------------------------------------------------*/

#include "sphKernel.H"
#include "IStringStream.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

using namespace Foam;

namespace
{

//- Smoothing lengths each test runs with [m]
const scalar smoothingLengths[] = {0.01, 1, 3};

//- Call test(kernel, h) for every kernel struct and smoothing length, with
//  both in the failure messages
template<class Test>
void forEachKernelAndSmoothingLength(Test&& test)
{
    auto withEachH = [&](auto kernel)
    {
        for (const scalar h : smoothingLengths)
        {
            SCOPED_TRACE
            (
                std::string(decltype(kernel)::name)
              + " h = " + std::to_string(h)
            );
            test(kernel, h);
        }
    };
    withEachH(sphKernels::WendlandC2{});
    withEachH(sphKernels::cubicSpline{});
    withEachH(sphKernels::quinticSpline{});
}

//- Kernel selected from the text of a system/spemSchemes dictionary
autoPtr<sphKernel> selectKernel(const std::string& schemesText)
{
    IStringStream is(schemesText);
    const dictionary schemesDict(is);
    return sphKernel::New(schemesDict);
}

//- A fine regular lattice: spacing h/latticeRefinement, for the discrete
//  sums to approach the integrals they stand for (measured deviations at
//  4: below 4e-5 for the sum of W, 1.6e-4 for the gradient moment)
constexpr scalar latticeRefinement = 4;

//- Call term(dx, dy, V) for every lattice point within the support of a
//  kernel centred at a point offset (by offsetX, offsetY lattice spacings)
//  from a lattice point; (dx, dy) = x_j - x_i, V the lattice cell area
template<class Kernel, class Term>
void forEachLatticeNeighbour
(
    const scalar h,
    const scalar offsetX,
    const scalar offsetY,
    Term&& term
)
{
    const scalar spacing = h/latticeRefinement;
    const int n = int(std::ceil(Kernel::support*latticeRefinement)) + 2;
    for (int i = -n; i <= n; ++i)
    {
        for (int j = -n; j <= n; ++j)
        {
            term
            (
                (i - offsetX)*spacing,
                (j - offsetY)*spacing,
                spacing*spacing
            );
        }
    }
}

} // End anonymous namespace


TEST(Kernels, integralOverThePlaneIsOne)
{
    forEachKernelAndSmoothingLength([](auto kernel, const scalar h)
    {
        using Kernel = decltype(kernel);

        // Polar quadrature, 2 pi int_0^{support h} W r dr, by composite
        // Simpson; the interval count puts the breaks of the piecewise
        // polynomials (q = 1, 2) on panel ends
        const int nIntervals = 6000;
        const scalar R = Kernel::support*h;
        const scalar dr = R/nIntervals;
        scalar integral = 0;
        for (int k = 0; k <= nIntervals; ++k)
        {
            const scalar r = k*dr;
            const scalar weight =
                (k == 0 || k == nIntervals) ? 1 : (k % 2 ? 4 : 2);
            integral += weight*r*Kernel::W(r, h);
        }
        integral *= constant::mathematical::twoPi*dr/3;

        std::cout << Kernel::name << " h = " << h
            << ": integral of W - 1 = " << integral - 1 << std::endl;
        EXPECT_NEAR(integral, 1, 1e-6);
    });
}


TEST(Kernels, latticeSumOfWIsOne)
{
    forEachKernelAndSmoothingLength([](auto kernel, const scalar h)
    {
        using Kernel = decltype(kernel);
        for (const scalar offset : {0.0, 0.37})
        {
            scalar sum = 0;
            forEachLatticeNeighbour<Kernel>
            (
                h, offset, 0.5*offset,
                [&](scalar dx, scalar dy, scalar V)
                {
                    sum += Kernel::W(std::hypot(dx, dy), h)*V;
                }
            );
            std::cout << Kernel::name << " h = " << h << " offset "
                << offset << ": lattice sum of W - 1 = " << sum - 1
                << std::endl;
            EXPECT_NEAR(sum, 1, 1e-3) << "offset " << offset;
        }
    });
}


TEST(Kernels, vanishOutsideTheirSupport)
{
    forEachKernelAndSmoothingLength([](auto kernel, const scalar h)
    {
        using Kernel = decltype(kernel);
        const scalar R = Kernel::support*h;
        for (const scalar r : {R, R*(1 + 1e-12), 1.01*R, 2*R, 100*R})
        {
            EXPECT_EQ(Kernel::W(r, h), 0) << "r/h = " << r/h;
            EXPECT_EQ(Kernel::F(r, h), 0) << "r/h = " << r/h;
        }
        // The support is not smaller than claimed, and W and F fall
        // continuously to zero at its edge: no step that a neighbour search
        // of radius support*h would cut off
        const scalar inside = R*(1 - 1e-6);
        EXPECT_GT(Kernel::W(inside, h), 0);
        EXPECT_LT(Kernel::F(inside, h), 0);
        EXPECT_LT(Kernel::W(inside, h), 1e-12*Kernel::W(0, h));
        EXPECT_LT(-Kernel::F(inside, h), -1e-9*Kernel::F(0, h));
    });
}


TEST(Kernels, gradientFactorIsDerivativeOverDistance)
{
    forEachKernelAndSmoothingLength([](auto kernel, const scalar h)
    {
        using Kernel = decltype(kernel);

        // Fractions of the support away from the breaks at q = 1, 2, where
        // a central difference would straddle a jump of a higher derivative
        const scalar dr = 1e-6*h;
        for (const scalar fraction : {0.05, 0.2, 0.4, 0.6, 0.8, 0.95})
        {
            const scalar r = fraction*Kernel::support*h;
            const scalar dWdr =
                (Kernel::W(r + dr, h) - Kernel::W(r - dr, h))/(2*dr);
            const scalar F = Kernel::F(r, h);
            EXPECT_NEAR(F, dWdr/r, 1e-6*std::abs(F)) << "r/h = " << r/h;
        }

        // Finite at the particle itself, continuous into r = 0
        const scalar F0 = Kernel::F(0, h);
        EXPECT_TRUE(std::isfinite(F0));
        EXPECT_LT(F0, 0);
        EXPECT_NEAR(Kernel::F(1e-7*h, h), F0, 1e-6*std::abs(F0));
    });
}


TEST(Kernels, latticeGradientFirstMomentIsIdentity)
{
    // sum_j (x_j - x_i) (x) grad_i W_ij V_j = I, the moment the FPM
    // correction restores near boundaries (paper sect. 2.2). With
    // grad_i W_ij = (x_i - x_j) F and y = x_j - x_i it reads
    // sum_j y y^T F V_j = -I: the integral of y_a dW/dy_b is -delta_ab by
    // parts, as W is normalised. Tests F's sign and scale with h.
    forEachKernelAndSmoothingLength([](auto kernel, const scalar h)
    {
        using Kernel = decltype(kernel);
        for (const scalar offset : {0.0, 0.37})
        {
            scalar moment[2][2] = {{0, 0}, {0, 0}};
            forEachLatticeNeighbour<Kernel>
            (
                h, offset, 0.5*offset,
                [&](scalar dx, scalar dy, scalar V)
                {
                    const scalar F = Kernel::F(std::hypot(dx, dy), h);
                    const scalar y[2] = {dx, dy};
                    const scalar gradW[2] = {-dx*F, -dy*F};
                    for (int a = 0; a < 2; ++a)
                    {
                        for (int b = 0; b < 2; ++b)
                        {
                            moment[a][b] += y[a]*gradW[b]*V;
                        }
                    }
                }
            );
            scalar maxDeviation = 0;
            for (int a = 0; a < 2; ++a)
            {
                for (int b = 0; b < 2; ++b)
                {
                    const scalar deviation = moment[a][b] - (a == b);
                    maxDeviation = std::max(maxDeviation, std::abs(deviation));
                    EXPECT_NEAR(deviation, 0, 1e-3)
                        << "component " << a << b << ", offset " << offset;
                }
            }
            std::cout << Kernel::name << " h = " << h << " offset "
                << offset << ": max |moment - I| = " << maxDeviation
                << std::endl;
        }
    });
}


TEST(Kernels, positiveAndDecreasingWithNonPositiveGradientFactor)
{
    forEachKernelAndSmoothingLength([](auto kernel, const scalar h)
    {
        using Kernel = decltype(kernel);
        const int nSamples = 2000;
        const scalar R = Kernel::support*h;
        scalar previous = Kernel::W(0, h);
        for (int k = 1; k <= nSamples; ++k)
        {
            // Samples up to 1.1 R: past the support too
            const scalar r = 1.1*R*k/nSamples;
            const scalar W = Kernel::W(r, h);
            const scalar F = Kernel::F(r, h);
            if (r < R)
            {
                ASSERT_GT(W, 0) << "r/h = " << r/h;
                ASSERT_LT(W, previous) << "r/h = " << r/h;
                ASSERT_LT(F, 0) << "r/h = " << r/h;
            }
            else
            {
                ASSERT_EQ(W, 0) << "r/h = " << r/h;
                ASSERT_EQ(F, 0) << "r/h = " << r/h;
            }
            previous = W;
        }
    });
}


TEST(Kernels, selectedByKernelKeywordWithWendlandC2Default)
{
    EXPECT_EQ(selectKernel("kernel cubicSpline;")->type(), "cubicSpline");
    EXPECT_EQ(selectKernel("kernel quinticSpline;")->type(), "quinticSpline");
    EXPECT_EQ(selectKernel("kernel WendlandC2;")->type(), "WendlandC2");
    EXPECT_EQ(selectKernel("method SPEM;")->type(), "WendlandC2");
    EXPECT_EQ(selectKernel("")->type(), "WendlandC2");

    // The selected object evaluates its own formula
    const autoPtr<sphKernel> quintic = selectKernel("kernel quinticSpline;");
    EXPECT_EQ(quintic->support(), 3);
    EXPECT_EQ(quintic->W(0.5, 1), sphKernels::quinticSpline::W(0.5, 1));
    EXPECT_EQ(quintic->F(0.5, 1), sphKernels::quinticSpline::F(0.5, 1));
}


TEST(Kernels, unknownKernelStopsListingValidNames)
{
    // Throw instead of exiting; returns the previous setting
    const bool wasThrowing = FatalIOError.throwExceptions();
    std::string message;
    try
    {
        selectKernel("kernel gaussian;");
        ADD_FAILURE() << "kernel gaussian was accepted";
    }
    catch (const IOerror& err)
    {
        message = err.message();
    }
    FatalIOError.throwExceptions(wasThrowing);
    std::cout << "FatalIOError message:\n" << message << std::endl;

    EXPECT_NE(message.find("gaussian"), std::string::npos) << message;
    for (const char* valid : {"WendlandC2", "cubicSpline", "quinticSpline"})
    {
        EXPECT_NE(message.find(valid), std::string::npos)
            << "valid name " << valid << " not listed in\n" << message;
    }
}


TEST(Kernels, visitHandsOverTheSelectedStruct)
{
    for (const char* name : {"WendlandC2", "cubicSpline", "quinticSpline"})
    {
        SCOPED_TRACE(name);
        const autoPtr<sphKernel> kernel =
            selectKernel(std::string("kernel ") + name + ";");

        const std::string visited = kernel->visit
        (
            [](auto k) { return std::string(decltype(k)::name); }
        );
        EXPECT_EQ(visited, name);

        for (const scalar h : smoothingLengths)
        {
            for (const scalar q : {0.0, 0.3, 0.9, 1.1, 1.5, 1.99, 2.5, 3.5})
            {
                const scalar r = q*h;
                const scalar W = kernel->visit
                (
                    [&](auto k) { return decltype(k)::W(r, h); }
                );
                const scalar F = kernel->visit
                (
                    [&](auto k) { return decltype(k)::F(r, h); }
                );
                EXPECT_EQ(W, kernel->W(r, h)) << "h " << h << " q " << q;
                EXPECT_EQ(F, kernel->F(r, h)) << "h " << h << " q " << q;
            }
        }
        EXPECT_EQ
        (
            kernel->visit([](auto k) { return decltype(k)::support; }),
            kernel->support()
        );
    }
}


// ************************************************************************* //
