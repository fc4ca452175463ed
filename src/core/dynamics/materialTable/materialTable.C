#include "materialTable.H"
#include "coreError.H"

namespace immersedDEM
{

materialTable::materialTable(std::vector<contactMaterial> materials)
:
    materials_(std::move(materials))
{
    if (materials_.empty())
    {
        throw coreError("The DEM needs at least one material");
    }
    for (const contactMaterial& m : materials_)
    {
        m.check();
    }
    for (const contactMaterial& a : materials_)
    {
        for (const contactMaterial& b : materials_)
        {
            pairs_.push_back(pairMaterial::of(a, b));
        }
    }
}

} // End namespace immersedDEM
