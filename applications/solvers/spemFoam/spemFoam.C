#include "argList.H"
#include "Time.H"
#include "triMesh.H"

using namespace Foam;

int main(int argc, char *argv[])
{
    #include "setRootCase.H"
    #include "createTime.H"
    triMesh mesh(triMesh::read(runTime));
    Info<< "triangles " << mesh.nTriangles() << endl;
    return 0;
}
