/*---------------------------------------------------------------------------*\
Description
    The last line of defence for errors of the core (immersedDEM::coreError)
    that no caller turned into an OpenFOAM error: instead of std::terminate's
    abort ("terminate called after throwing ...", a core dump and a signal),
    the message goes out as a FOAM FATAL ERROR and the process exits with
    status 1 (in parallel through OpenFOAM's own abort of all ranks).

    Installed when libimmersedDEM.so is loaded (the solver's libs entry, or
    the runners linked against it). Other exceptions get the same treatment
    with what they say; anything else falls through to the default abort.
\*---------------------------------------------------------------------------*/

#include "error.H"
#include "coreError.H"

#include <exception>

namespace
{

std::terminate_handler previousHandler = nullptr;

[[noreturn]] void coreErrorTerminate()
{
    if (const std::exception_ptr e = std::current_exception())
    {
        try
        {
            std::rethrow_exception(e);
        }
        catch (const immersedDEM::coreError& err)
        {
            FatalErrorInFunction
                << err.what() << Foam::nl
                << "(an error of immersedDEM that reached the top: please"
                << " report the case that led here)" << Foam::exit(Foam::FatalError);
        }
        catch (const std::bad_alloc&)
        {
            FatalErrorInFunction
                << "out of memory (std::bad_alloc): reduce the case's size"
                << " (cells, bodies, virtual-mesh level) or run it on more"
                << " processors" << Foam::exit(Foam::FatalError);
        }
        catch (const std::exception& err)
        {
            FatalErrorInFunction
                << err.what() << Foam::exit(Foam::FatalError);
        }
        catch (...)
        {}
    }
    if (previousHandler)
    {
        previousHandler();
    }
    std::abort();
}

struct installer
{
    installer()
    {
        previousHandler = std::set_terminate(coreErrorTerminate);
    }
};

const installer install;

} // End anonymous namespace
