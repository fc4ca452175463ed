#include "sizeDistribution.H"
#include "coreError.H"

#include <cmath>
#include <limits>

namespace immersedDEM
{

namespace
{
void checkFactor(double f, const char* what)
{
    if (!(f > 0) || !std::isfinite(f))
    {
        throw coreError
        (
            std::string("size factor ") + what + " is " + std::to_string(f)
          + "; it must be > 0"
        );
    }
}
}


sizeDistribution sizeDistribution::fixed(double value)
{
    checkFactor(value, "value");
    sizeDistribution d;
    d.kind_ = kind::fixed;
    d.a_ = d.b_ = d.lo_ = d.hi_ = value;
    return d;
}


sizeDistribution sizeDistribution::uniform(double min, double max)
{
    checkFactor(min, "min");
    checkFactor(max, "max");
    if (min > max)
    {
        throw coreError("size factor min > max");
    }
    sizeDistribution d;
    d.kind_ = kind::uniform;
    d.a_ = d.lo_ = min;
    d.b_ = d.hi_ = max;
    return d;
}


sizeDistribution sizeDistribution::normal(double mean, double sd, double min, double max)
{
    checkFactor(mean, "mean");
    checkFactor(min, "min");
    checkFactor(max, "max");
    if (!(sd >= 0) || !std::isfinite(sd))
    {
        throw coreError("size factor standardDeviation must be >= 0");
    }
    if (min > max || mean < min || mean > max)
    {
        throw coreError("size factor: min <= mean <= max is needed");
    }
    sizeDistribution d;
    d.kind_ = kind::normal;
    d.a_ = mean;
    d.b_ = sd;
    d.lo_ = min;
    d.hi_ = max;
    return d;
}


sizeDistribution sizeDistribution::normal(double mean, double sd)
{
    checkFactor(mean, "mean");
    return normal(mean, sd, std::max(mean - 3*sd, 1e-3*mean), mean + 3*sd);
}


sizeDistribution sizeDistribution::table(const std::vector<std::pair<double, double>>& rows)
{
    if (rows.empty())
    {
        throw coreError("size factor table is empty");
    }
    sizeDistribution d;
    d.kind_ = kind::table;
    double sum = 0;
    d.lo_ = std::numeric_limits<double>::max();
    d.hi_ = 0;
    for (const auto& r : rows)
    {
        checkFactor(r.first, "in the table");
        if (!(r.second >= 0) || !std::isfinite(r.second))
        {
            throw coreError("size factor table: a weight is negative");
        }
        sum += r.second;
    }
    if (!(sum > 0))
    {
        throw coreError("size factor table: the weights sum to 0");
    }
    double c = 0;
    for (const auto& r : rows)
    {
        if (r.second == 0) continue;
        c += r.second/sum;
        d.table_.emplace_back(r.first, c);
        d.lo_ = std::min(d.lo_, r.first);
        d.hi_ = std::max(d.hi_, r.first);
    }
    d.table_.back().second = 1;
    return d;
}


double sizeDistribution::uniform01(std::mt19937_64& rng)
{
    return double(rng() >> 11)*(1.0/9007199254740992.0);
}


double sizeDistribution::standardNormal(std::mt19937_64& rng)
{
    // Box-Muller on (0, 1]
    const double u1 = 1 - uniform01(rng);
    const double u2 = uniform01(rng);
    return std::sqrt(-2*std::log(u1))*std::cos(2*M_PI*u2);
}


double sizeDistribution::sample(std::mt19937_64& rng) const
{
    switch (kind_)
    {
        case kind::fixed:
            return a_;
        case kind::uniform:
            return a_ + (b_ - a_)*uniform01(rng);
        case kind::normal:
        {
            if (b_ == 0) return a_;
            for (int i = 0; i < 1000000; ++i)
            {
                const double f = a_ + b_*standardNormal(rng);
                if (f >= lo_ && f <= hi_) return f;
            }
            throw coreError("size factor: [min, max] is too far out in the normal's tail");
        }
        case kind::table:
        {
            const double u = uniform01(rng);
            for (const auto& r : table_)
            {
                if (u < r.second) return r.first;
            }
            return table_.back().first;
        }
    }
    return a_;
}

} // End namespace immersedDEM
