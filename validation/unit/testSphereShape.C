#include "sphereShape.H"
#include "coreError.H"

#include <gtest/gtest.h>

using namespace immersedDEM;

TEST(sphereShape, massProperties)
{
    const sphereShape s(0.005);
    EXPECT_NEAR(s.volume(), 4.0/3.0*M_PI*1.25e-7, 1e-20);
    EXPECT_NEAR(s.principalMoments()[0], 0.4*s.volume()*2.5e-5, 1e-25);
}

TEST(sphereShape, badRadius)
{
    EXPECT_THROW(sphereShape(0), coreError);
    EXPECT_THROW(sphereShape(-1), coreError);
    EXPECT_THROW(sphereShape(std::nan("")), coreError);
}
