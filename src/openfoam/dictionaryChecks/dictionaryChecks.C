#include "dictionaryChecks.H"
#include "IOstreams.H"

void Foam::immersedDEMChecks::allowOnly(const dictionary& dict, const wordList& allowed)
{
    for (const entry& e : dict)
    {
        if (!allowed.found(e.keyword()))
        {
            FatalIOErrorInFunction(dict)
                << "Unknown keyword '" << e.keyword() << "' in "
                << dict.name() << nl
                << "Valid keywords: " << allowed << nl
                << exit(FatalIOError);
        }
    }
}


Foam::scalar Foam::immersedDEMChecks::positive
(
    const dictionary& dict,
    const word& key,
    bool zeroAllowed
)
{
    const scalar v = dict.get<scalar>(key);
    if (!(zeroAllowed ? v >= 0 : v > 0) || !std::isfinite(v))
    {
        FatalIOErrorInFunction(dict)
            << "Keyword '" << key << "' in " << dict.name() << " is " << v
            << "; it must be " << (zeroAllowed ? ">= 0" : "> 0") << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::scalar Foam::immersedDEMChecks::positiveOrDefault
(
    const dictionary& dict,
    const word& key,
    scalar def
)
{
    return dict.found(key, keyType::LITERAL) ? positive(dict, key) : def;
}


Foam::scalar Foam::immersedDEMChecks::inRange
(
    const dictionary& dict,
    const word& key,
    scalar lo,
    scalar hi
)
{
    const scalar v = dict.get<scalar>(key);
    if (!(v >= lo && v <= hi))
    {
        FatalIOErrorInFunction(dict)
            << "Keyword '" << key << "' in " << dict.name() << " is " << v
            << "; it must be in [" << lo << ", " << hi << "]" << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::scalar Foam::immersedDEMChecks::inRangeOrDefault
(
    const dictionary& dict,
    const word& key,
    scalar lo,
    scalar hi,
    scalar def
)
{
    return dict.found(key, keyType::LITERAL) ? inRange(dict, key, lo, hi) : def;
}


Foam::word Foam::immersedDEMChecks::oneOf
(
    const dictionary& dict,
    const word& key,
    const wordList& valid
)
{
    const word v = dict.get<word>(key);
    if (!valid.found(v))
    {
        FatalIOErrorInFunction(dict)
            << "Unknown " << key << " '" << v << "' in " << dict.name() << nl
            << "Valid " << key << " types are: " << valid << nl
            << exit(FatalIOError);
    }
    return v;
}


Foam::word Foam::immersedDEMChecks::oneOfOrDefault
(
    const dictionary& dict,
    const word& key,
    const wordList& valid,
    const word& def
)
{
    return dict.found(key, keyType::LITERAL) ? oneOf(dict, key, valid) : def;
}


const Foam::dictionary& Foam::immersedDEMChecks::subDictEntry
(
    const dictionary& parent,
    const entry& e,
    const char* what
)
{
    if (!e.isDict())
    {
        FatalIOErrorInFunction(parent)
            << "Entry '" << e.keyword() << "' in " << parent.name()
            << " must be a dictionary of " << what << nl
            << exit(FatalIOError);
    }
    return e.dict();
}
