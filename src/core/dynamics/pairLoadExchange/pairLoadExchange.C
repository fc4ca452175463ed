#include "pairLoadExchange.H"
#include "coreError.H"

#include <algorithm>

namespace immersedDEM
{

void pairLoadExchange::gather
(
    demCommunicator& comm,
    std::vector<pairLoad>& loads,
    std::vector<contactRecord>& contacts,
    contactHistoryTable& next
)
{
    // This process's pairs, flat: per pair a, b, film, its region count,
    // its eight load vectors, then per region the contact record and the
    // history the law left
    std::vector<double> mine;
    auto put3 = [&mine](const vec3& v) { mine.insert(mine.end(), {v.x(), v.y(), v.z()}); };
    mine.push_back(double(loads.size()));
    for (const pairLoad& l : loads)
    {
        const size_t nr = l.contactsTo - l.contactsFrom;
        mine.insert(mine.end(), {double(l.a), double(l.b), double(l.film), double(nr)});
        for (const vec3* v : {&l.forceA, &l.torqueA, &l.forceB, &l.torqueB,
            &l.filmForceA, &l.filmTorqueA, &l.filmForceB, &l.filmTorqueB})
        {
            put3(*v);
        }
        contactHistoryTable::range hs;
        if (nr > 0)
        {
            hs = next.find(std::make_pair(l.a, l.b));
            if (hs.size() != nr)
            {
                throw coreError("pairLoadExchange: a pair's contact histories do not match its contacts");
            }
        }
        for (size_t k = 0; k < nr; ++k)
        {
            const contactRecord& c = contacts[l.contactsFrom + k];
            const contactRegion& r = c.region;
            mine.push_back(r.volume);
            put3(r.point);
            put3(r.normal);
            mine.push_back(r.area);
            put3(r.areaVector);
            put3(r.areaMoment);
            const contactOutput& f = c.force;
            put3(f.force);
            mine.push_back(f.normalForce);
            put3(f.tangentialForce);
            put3(f.couple);
            mine.push_back(double(f.sliding));
            const contactHistory& h = hs.first[k];
            put3(h.tangentialSpring);
            put3(h.normal);
            put3(h.point);
            mine.push_back(h.approach);
            mine.push_back(h.maxNormalForce);
            mine.push_back(h.twist);
            put3(h.rolling);
        }
    }

    const std::vector<std::vector<double>> all = comm.allGather(mine);

    // Every process's pairs, read back, in the order of the pairs (each
    // process's are in that order already; a pair has one owner)
    struct gathered
    {
        pairLoad load;
        std::vector<contactRecord> contacts;
        std::vector<contactHistory> histories;
    };
    std::vector<gathered> pairs;
    for (const std::vector<double>& buf : all)
    {
        size_t at = 0;
        auto get = [&buf, &at]() { return buf.at(at++); };
        auto get3 = [&get]() { const double x = get(), y = get(), z = get(); return vec3(x, y, z); };
        const size_t nPairs = size_t(get());
        for (size_t k = 0; k < nPairs; ++k)
        {
            gathered g;
            pairLoad& l = g.load;
            l.a = int(get());
            l.b = int(get());
            l.film = get() != 0;
            const size_t nr = size_t(get());
            for (vec3* v : {&l.forceA, &l.torqueA, &l.forceB, &l.torqueB,
                &l.filmForceA, &l.filmTorqueA, &l.filmForceB, &l.filmTorqueB})
            {
                *v = get3();
            }
            for (size_t j = 0; j < nr; ++j)
            {
                contactRecord c;
                c.a = l.a;
                c.b = l.b;
                contactRegion& r = c.region;
                r.volume = get();
                r.point = get3();
                r.normal = get3();
                r.area = get();
                r.areaVector = get3();
                r.areaMoment = get3();
                contactOutput& f = c.force;
                f.force = get3();
                f.normalForce = get();
                f.tangentialForce = get3();
                f.couple = get3();
                f.sliding = get() != 0;
                contactHistory h;
                h.tangentialSpring = get3();
                h.normal = get3();
                h.point = get3();
                h.approach = get();
                h.maxNormalForce = get();
                h.twist = get();
                h.rolling = get3();
                g.contacts.push_back(c);
                g.histories.push_back(h);
            }
            pairs.push_back(std::move(g));
        }
        if (at != buf.size())
        {
            throw coreError("pairLoadExchange: a process's contact loads were not read whole");
        }
    }
    std::sort
    (
        pairs.begin(), pairs.end(),
        [](const gathered& x, const gathered& y)
        {
            return std::make_pair(x.load.a, x.load.b) < std::make_pair(y.load.a, y.load.b);
        }
    );
    loads.clear();
    contacts.clear();
    next.clear();
    for (gathered& g : pairs)
    {
        g.load.contactsFrom = contacts.size();
        contacts.insert(contacts.end(), g.contacts.begin(), g.contacts.end());
        g.load.contactsTo = contacts.size();
        if (!g.histories.empty())
        {
            next.beginPair(std::make_pair(g.load.a, g.load.b));
            for (const contactHistory& h : g.histories) next.add(h);
        }
        loads.push_back(g.load);
    }
}

} // End namespace immersedDEM
